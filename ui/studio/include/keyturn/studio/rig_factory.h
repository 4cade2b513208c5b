#pragma once
// How the studio opens devices. The application supplies the implementation
// (real drivers, and the simulated rig); the GUI only says what the user chose.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"

namespace keyturn::studio {

// A dataset replayed as the camera and the pose source (rig/dataset_playback.h).
struct PlaybackRequest {
  std::string dataset;
  double rate_fps = 0;  // 0: the recorded rate
  bool loop = true;
  bool operator==(const PlaybackRequest& o) const { return dataset == o.dataset && rate_fps == o.rate_fps && loop == o.loop; }
};

struct CameraRequest {
  enum class Kind { Simulated, Usb, Ethernet, Playback } kind = Kind::Simulated;
  unsigned usb_serial = 0;     // 0: the first camera found
  std::string address;         // Ethernet IPv4
  std::string sim_object;      // Simulated: the object on the simulated turntable (a name from simObjects())
  double sim_elevation_deg = 30;
  double sim_distance_m = 0;   // 0: where an operator would place the camera
  PlaybackRequest playback;    // Playback: the recording
  std::string describe() const;
};

struct PoseRequest {
  enum class Kind { None, Simulated, ModbusTcp, ModbusRtu, Can, Playback } kind = Kind::Simulated;
  std::string endpoint;        // HOST:PORT, a serial device, or a CAN interface
  std::string profile = "keyturn-sim";  // Modbus register profile, or the CANopen axes file
  PlaybackRequest playback;    // Playback: the camera's recording (the same one: its pose follows its frames)
  std::string describe() const;
};

struct SimObject {
  std::string cls, instance, mesh;  // mesh: a PLY path or builtin:NAME
};

class RigFactory {
 public:
  using Log = std::function<void(const std::string&)>;
  virtual ~RigFactory() = default;
  // Both throw keyturn::Error naming the device and what went wrong.
  virtual std::unique_ptr<drivers::TofCamera> openCamera(const CameraRequest& request, Log log) = 0;
  virtual std::unique_ptr<drivers::PoseSource> openPose(const PoseRequest& request, Log log) = 0;
  virtual std::vector<SimObject> simObjects() const = 0;
  // The simulated camera's cable: pulled (opens and frames fail) or plugged in.
  virtual void setSimulatedCameraUnplugged(bool unplugged) = 0;
  // "SR4000 4000123 on USB 1-2" lines for the USB camera list; throws when USB is unusable.
  virtual std::vector<std::pair<unsigned, std::string>> usbCameras() = 0;
  // Handles pending USB hot-plug events without waiting: true when a SwissRanger
  // arrived or left since the last call. False where libusb has no hot-plug.
  virtual bool usbCamerasChanged() { return false; }
  // Camera ← turntable at 0° for the views' sidecars: exact for the simulated
  // rig, from an axis calibration for a real one, none when not calibrated.
  virtual std::optional<Eigen::Matrix4d> cameraFromTurntable() const { return std::nullopt; }
};

}  // namespace keyturn::studio
