#pragma once
// The studio's devices: the real drivers (SR4000 over USB or Ethernet through
// libMesaSR, Modbus RTU/TCP turntables, CANopen axes over SocketCAN) and the
// simulated rig (rig/simulated_rig.h: libmesasr-sim and the simulated Modbus
// turntable, sharing a world file in a private runtime folder).
#include <mutex>

#include "keyturn/drivers/usb_discovery.h"
#include "keyturn/rig/dataset_playback.h"
#include "keyturn/rig/simulated_rig.h"
#include "keyturn/studio/rig_factory.h"

namespace keyturn::studio {

class StudioRigFactory final : public RigFactory {
 public:
  // objects_csv: the simulated objects (data/objects/objects.csv).
  explicit StudioRigFactory(std::string objects_csv);
  ~StudioRigFactory() override;

  std::unique_ptr<drivers::TofCamera> openCamera(const CameraRequest& request, Log log) override;
  std::unique_ptr<drivers::PoseSource> openPose(const PoseRequest& request, Log log) override;
  std::vector<SimObject> simObjects() const override { return objects_; }
  void setSimulatedCameraUnplugged(bool unplugged) override;
  std::vector<std::pair<unsigned, std::string>> usbCameras() override;
  bool usbCamerasChanged() override;
  std::optional<Eigen::Matrix4d> cameraFromTurntable() const override;
  const std::string& runtimeDir() const { return files_.dir; }

 private:
  // The camera and the pose source of one recording share its timeline, whichever opens first.
  std::shared_ptr<rig::Recording> recording(const PlaybackRequest& request);

  std::vector<SimObject> objects_;
  rig::SimulatedRigFiles files_;
  mutable std::mutex mutex_;
  std::optional<Eigen::Matrix4d> camera_from_turntable_;
  std::unique_ptr<drivers::UsbHotplugWatcher> hotplug_;
  bool hotplug_tried_ = false, usb_changed_ = false;
  PlaybackRequest playing_;
  std::shared_ptr<rig::Recording> recording_;
};

}  // namespace keyturn::studio
