#pragma once
// The devices of one capture, opened through the device factory (device_factory.h): the
// simulated rig's camera and, with pose sim, its turntable (simulated_rig.h), a recording's
// camera and poses, or a real camera and pose source. Opened in the order that names a bad one
// before anything is written: the pose source (and its profile) before the camera.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "keyturn/core/error.h"
#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/rig/device_factory.h"
#include "keyturn/rig/device_spec.h"
#include "keyturn/rig/simulated_rig.h"

namespace keyturn::rig {

struct CaptureDevices {
  CameraSpec camera;         // simulated (configured by sim below), usb, eth, playback, or openni2 (with pose
                             // sim: the simulated rig's camera through the simulated OpenNI2 driver)
  PoseSpec pose;             // sim: the simulated or played-back rig's own; playback; or a real pose source
  SimulatedRigOptions sim;   // with a simulated camera (simulated_pose follows pose)
};

// The simulated turntable asked for with a camera that is not simulated: the simulated table and
// camera share one world. Typed, so the CLI can word it in its flags.
struct SimulatedTurntableNeedsSimulatedCamera : Error {
  SimulatedTurntableNeedsSimulatedCamera();
};

class CaptureRig {
 public:
  // Throws keyturn::Error naming the device or the combination (pose sim without a simulated camera).
  explicit CaptureRig(const CaptureDevices& devices);
  drivers::TofCamera& camera() { return *camera_; }
  drivers::PoseSource& pose() { return *pose_; }
  // Exact in simulation; none for real devices (a measured calibration supplies it).
  const std::optional<Eigen::Matrix4d>& cameraFromTurntable() const { return camera_from_turntable_; }
  // The simulated turntable, when the pose is simulated (its server's counters), else null.
  const SimulatedTurntable* simulatedTurntable() const { return sim_.turntable.get(); }

 private:
  DeviceFactory factory_;
  SimulatedRig sim_;  // owns the simulated devices, when used
  std::unique_ptr<drivers::TofCamera> real_camera_;
  std::unique_ptr<drivers::PoseSource> real_pose_;
  drivers::TofCamera* camera_ = nullptr;
  drivers::PoseSource* pose_ = nullptr;
  std::optional<Eigen::Matrix4d> camera_from_turntable_;
};

// A capture from a recording into that recording would overwrite what it plays: refused, naming out.
void refusePlaybackInto(const CaptureDevices& devices, const std::string& out);

}  // namespace keyturn::rig
