#pragma once
// How the studio opens devices. The GUI says what the user chose as rig's typed
// specs (rig/device_spec.h); the implementation (StudioRigFactory) opens them
// through rig's one device factory, so the CLI and the studio open the same device.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/rig/device_spec.h"
#include "keyturn/rig/found_camera.h"

namespace keyturn::studio {

struct SimObject {
  std::string cls, instance, mesh;  // mesh: a PLY path or builtin:NAME
};

class RigFactory {
 public:
  using Log = std::function<void(const std::string&)>;
  virtual ~RigFactory() = default;
  // Both throw keyturn::Error naming the device and what went wrong.
  virtual std::unique_ptr<drivers::TofCamera> openCamera(const rig::CameraSpec& spec, Log log) = 0;
  virtual std::unique_ptr<drivers::PoseSource> openPose(const rig::PoseSpec& spec, Log log) = 0;
  virtual std::vector<SimObject> simObjects() const = 0;
  // The simulated camera looking at sim_object (an instance from simObjects(); unknown: the first)
  // on the studio's simulated turntable: its configuration written, the spec that opens it returned.
  virtual rig::CameraSpec simulatedCamera(const std::string& sim_object) = 0;
  // The simulated OpenNI2 camera's default device (keyturn-sim://default) as the studio opens it:
  // looking at sim_object on the studio's simulated turntable, as simulatedCamera's SR4000 does,
  // at a Kinect's 30 frames/s. A factory without a simulated rig opens the default device as it is.
  virtual rig::CameraSpec simulatedOpenNi2Camera(const std::string& /*sim_object*/) {
    return rig::openNi2CameraSpec(kSimulatedOpenNi2Default);
  }
  static constexpr const char* kSimulatedOpenNi2Default = "keyturn-sim://default";
  // The simulated camera's cable: pulled (opens and frames fail) or plugged in.
  virtual void setSimulatedCameraUnplugged(bool unplugged) = 0;
  // The SwissRangers on USB, each as the spec that opens it and its line in the list
  // (rig/found_camera.h); throws when USB is unusable.
  virtual std::vector<rig::FoundCamera> usbCameras() = 0;
  // Handles pending USB hot-plug events without waiting: true when a SwissRanger
  // arrived or left since the last call. False where libusb has no hot-plug.
  virtual bool usbCamerasChanged() { return false; }
  // The OpenNI2 depth cameras present, as usbCameras(); throws when OpenNI2 cannot start.
  virtual std::vector<rig::FoundCamera> openni2Cameras() { return {}; }
  // Camera ← turntable at 0° for the views' sidecars: exact for the simulated
  // rig, from an axis calibration for a real one, none when not calibrated.
  virtual std::optional<Eigen::Matrix4d> cameraFromTurntable() const { return std::nullopt; }
};

}  // namespace keyturn::studio
