#pragma once
// A Cartesian robot's (or encoders') pose over CANopen: per-axis nodes, CiA 406
// encoders (position value 0x6004) and CiA 402 drives (position actual value
// 0x6064), read by expedited SDO upload (0x600+id → 0x580+id) or from TPDO1
// (0x180+id) after setting the event timer (0x1800 sub 5) and starting the node.
//
// Axes file (JSON): [ {"name": "x", "node": 1, "device": "cia406", "scale": 1e-5, "offset": 0}, … ]
// with names x, y, z (metres) or turntable (degrees); scale is units per count.
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "keyturn/drivers/can_bus.h"
#include "keyturn/drivers/pose_source.h"

namespace keyturn::drivers {

struct CanOpenAxis {
  std::string name = "x";
  int node_id = 1;
  enum class Device { Encoder406, Drive402 } device = Device::Encoder406;
  double scale = 1e-6;
  double offset = 0;

  static std::vector<CanOpenAxis> loadAll(const std::string& path);  // throws keyturn::Error
};

struct CanOpenOptions {
  bool use_tpdo = false;
  int event_timer_ms = 10;
  int sdo_timeout_ms = 100;
  int retries = 2;
};

class CanOpenPoseSource final : public PoseSource {
 public:
  CanOpenPoseSource(std::unique_ptr<CanBus> bus, std::vector<CanOpenAxis> axes, CanOpenOptions options = CanOpenOptions());
  Pose read() override;
  std::string describe() const override;

  std::uint32_t sdoUpload(int node, std::uint16_t index, std::uint8_t sub);
  void sdoDownload(int node, std::uint16_t index, std::uint8_t sub, std::uint32_t value, int bytes);

 private:
  std::uint32_t positionBySdo(const CanOpenAxis& a);
  void startTpdo();
  std::unique_ptr<CanBus> bus_;
  std::vector<CanOpenAxis> axes_;
  CanOpenOptions o_;
  std::map<int, std::int64_t> last_tpdo_;  // node → last position received
};

// Names a CANopen SDO abort code.
std::string sdoAbortText(std::uint32_t code);
std::uint16_t positionObject(CanOpenAxis::Device d);  // 0x6004 or 0x6064

}  // namespace keyturn::drivers
