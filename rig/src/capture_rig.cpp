#include "keyturn/rig/capture_rig.h"

#include <filesystem>

#include "keyturn/core/error.h"
#include "keyturn/rig/dataset_playback.h"
#include "keyturn/rig/devices.h"

namespace keyturn::rig {

namespace {
const char* const kSharedWorld = "--pose sim needs --camera sim: the simulated table and camera share one world";
}

CaptureRig::CaptureRig(const CaptureDevices& d) {
  if (isPlaybackSpec(d.camera)) {
    // The recording's own pose unless another source is named: like the simulated rig's, it comes with the camera.
    auto recording = std::make_shared<Recording>(playbackDataset(d.camera), playbackOptions(d.camera));
    if (d.pose == "sim" || d.pose == "playback") real_pose_ = std::make_unique<PlaybackPose>(recording);
    else real_pose_ = openPoseSource(d.pose, d.profile);
    real_camera_ = std::make_unique<PlaybackCamera>(recording);
    camera_ = real_camera_.get();
    pose_ = real_pose_.get();
    camera_from_turntable_ = recording->cameraFromTurntable();
    return;
  }
  if (d.pose == "playback") throw Error("--pose playback needs --camera playback:DATASET (the recording holds both)");
  if (d.camera == "sim") {
    SimulatedRigOptions so = d.sim;
    so.simulated_pose = d.pose == "sim";
    sim_ = openSimulatedRig(so);
    camera_ = sim_.camera.get();
    camera_from_turntable_ = sim_.camera_from_turntable;
  } else {
    (void)parseCameraSpec(d.camera);
    if (d.pose == "sim") throw Error(kSharedWorld);
    real_pose_ = openPoseSource(d.pose, d.profile);  // before the camera: a missing profile is said at once
    real_camera_ = openCamera(d.camera, "");
    camera_ = real_camera_.get();
  }
  if (d.pose == "sim") {
    if (!sim_.turntable) throw Error(kSharedWorld);
    pose_ = sim_.turntable.get();
  } else {
    if (!real_pose_) real_pose_ = openPoseSource(d.pose, d.profile);
    pose_ = real_pose_.get();
  }
}

void refusePlaybackInto(const CaptureDevices& d, const std::string& out) {
  if (!isPlaybackSpec(d.camera)) return;
  std::error_code ec;
  if (std::filesystem::equivalent(playbackDataset(d.camera), out, ec))
    throw Error(out + ": is the recording played back; capture into another folder");
}

}  // namespace keyturn::rig
