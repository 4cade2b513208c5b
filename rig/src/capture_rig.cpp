#include "keyturn/rig/capture_rig.h"

#include <filesystem>

#include "keyturn/core/error.h"

namespace keyturn::rig {

SimulatedTurntableNeedsSimulatedCamera::SimulatedTurntableNeedsSimulatedCamera()
    : Error("the simulated turntable needs the simulated SR4000 (sim) or the simulated OpenNI2 camera (openni2): the "
            "simulated table and camera share one world") {}

CaptureRig::CaptureRig(const CaptureDevices& d) {
  using CameraKind = CameraSpec::Kind;
  using PoseKind = PoseSpec::Kind;
  if (d.camera.kind == CameraKind::Playback) {
    // The recording's own pose unless another source is named: like the simulated rig's, it comes with the camera.
    PoseSpec pose = d.pose;
    if (pose.kind == PoseKind::Simulated) pose.kind = PoseKind::Playback;
    if (pose.kind == PoseKind::Playback && pose.playback.dataset.empty()) pose.playback = d.camera.playback;
    real_pose_ = factory_.openPoseSource(pose);
    real_camera_ = factory_.openCamera(d.camera);
    camera_ = real_camera_.get();
    pose_ = real_pose_.get();
    camera_from_turntable_ = factory_.cameraFromTurntable();
    return;
  }
  if (d.pose.kind == PoseKind::Playback) throw Error("a recording's poses need its camera too (playback:DATASET: the recording holds both)");
  // openni2 with the simulated turntable: the simulated rig's camera, seen through the simulated OpenNI2 driver.
  const bool simulated_openni2 =
      d.camera.kind == CameraKind::OpenNi2 && d.camera.openni2_uri.empty() && d.pose.kind == PoseKind::Simulated;
  if (d.camera.kind == CameraKind::Simulated || simulated_openni2) {
    if (!d.camera.sim_config.empty())
      throw Error("camera '" + d.camera.toString() +
                  "': a capture writes its simulated camera's configuration itself (mesh, distance, seed); give sim");
    SimulatedRigOptions so = d.sim;
    so.simulated_pose = d.pose.kind == PoseKind::Simulated;
    so.openni2 = simulated_openni2;
    if (!so.simulated_pose) real_pose_ = factory_.openPoseSource(d.pose);  // a missing profile is said at once
    sim_ = openSimulatedRig(so);
    camera_ = sim_.camera.get();
    camera_from_turntable_ = sim_.camera_from_turntable;
    pose_ = so.simulated_pose ? static_cast<drivers::PoseSource*>(sim_.turntable.get()) : real_pose_.get();
    return;
  }
  if (d.pose.kind == PoseKind::Simulated) throw SimulatedTurntableNeedsSimulatedCamera();
  real_pose_ = factory_.openPoseSource(d.pose);  // before the camera: a missing profile is said at once
  real_camera_ = factory_.openCamera(d.camera);
  camera_ = real_camera_.get();
  pose_ = real_pose_.get();
}

void refusePlaybackInto(const CaptureDevices& d, const std::string& out) {
  if (d.camera.kind != CameraSpec::Kind::Playback) return;
  std::error_code ec;
  if (std::filesystem::equivalent(d.camera.playback.dataset, out, ec))
    throw Error(out + ": is the recording played back; capture into another folder");
}

}  // namespace keyturn::rig
