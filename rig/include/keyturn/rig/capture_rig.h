#pragma once
// The devices of one capture, opened by name (devices.h): the simulated rig's
// camera and, with pose "sim", its turntable (simulated_rig.h), or a real camera
// and pose source. Opened in the order that names a bad one before anything is
// written: the pose source (and its profile) before the camera.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/rig/simulated_rig.h"

namespace keyturn::rig {

struct CaptureDevices {
  std::string camera = "sim";   // sim, usb, usb:SERIAL, eth:IP, playback:DATASET[@FPS]
  std::string pose = "sim";     // sim (the simulated or played-back rig's own), playback, or a pose source spec
  std::string profile;          // the pose source's profile
  SimulatedRigOptions sim;      // with camera sim (simulated_pose follows pose)
};

class CaptureRig {
 public:
  // Throws keyturn::Error naming the device or the combination (pose sim without camera sim).
  explicit CaptureRig(const CaptureDevices& devices);
  drivers::TofCamera& camera() { return *camera_; }
  drivers::PoseSource& pose() { return *pose_; }
  // Exact in simulation; none for real devices (a measured calibration supplies it).
  const std::optional<Eigen::Matrix4d>& cameraFromTurntable() const { return camera_from_turntable_; }
  // The simulated turntable, when the pose is simulated (its server's counters), else null.
  const SimulatedTurntable* simulatedTurntable() const { return sim_.turntable.get(); }

 private:
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
