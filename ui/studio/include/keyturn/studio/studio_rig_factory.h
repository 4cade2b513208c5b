#pragma once
// The studio's devices, opened by rig's device factory (rig/device_factory.h) as
// the CLI opens them. What is the studio's own: the simulated rig's files in a
// private runtime folder (the world the simulated camera and turntable share,
// the camera's configuration, its unplug flag: studio_runtime_folder.h), the simulated objects to choose
// from, and USB and OpenNI2 discovery for the Devices panel.
#include <mutex>

#include "keyturn/drivers/usb_discovery.h"
#include "keyturn/rig/device_factory.h"
#include "keyturn/rig/simulated_rig.h"
#include "keyturn/studio/rig_factory.h"
#include "keyturn/studio/studio_runtime_folder.h"

namespace keyturn::studio {

class StudioRigFactory final : public RigFactory {
 public:
  // objects_csv: the simulated objects (data/objects/objects.csv). noise_per_pose: the simulated
  // cameras draw their noise once per turntable angle (a still table gives equal frames: the tests'
  // deterministic recognition), else once per frame as a sensor does.
  explicit StudioRigFactory(std::string objects_csv, bool noise_per_pose = false);
  ~StudioRigFactory() override;

  std::unique_ptr<drivers::TofCamera> openCamera(const rig::CameraSpec& spec, Log log) override;
  std::unique_ptr<drivers::PoseSource> openPose(const rig::PoseSpec& spec, Log log) override;
  std::vector<SimObject> simObjects() const override { return objects_; }
  rig::CameraSpec simulatedCamera(const std::string& sim_object) override;
  rig::CameraSpec simulatedOpenNi2Camera(const std::string& sim_object) override;
  void setSimulatedCameraUnplugged(bool unplugged) override;
  std::vector<rig::FoundCamera> usbCameras() override;
  bool usbCamerasChanged() override;
  std::vector<rig::FoundCamera> openni2Cameras() override;
  std::optional<Eigen::Matrix4d> cameraFromTurntable() const override;
  const std::string& runtimeDir() const { return files_.dir; }

 private:
  StudioRuntimeFolder folder_;  // first made, last removed: the simulated devices write into it
  std::vector<SimObject> objects_;
  rig::SimulatedRigFiles files_;
  std::unique_ptr<rig::DeviceFactory> devices_;  // its simulated turntable writes files_.world()
  bool noise_per_pose_ = false;
  std::mutex config_mutex_;                      // simulatedCamera writes one configuration at a time
  std::unique_ptr<drivers::UsbHotplugWatcher> hotplug_;
  bool hotplug_tried_ = false, usb_changed_ = false;
};

}  // namespace keyturn::studio
