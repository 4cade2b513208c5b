#include "keyturn/rig/capture_rig.h"

#include "keyturn/core/error.h"
#include "keyturn/rig/devices.h"

namespace keyturn::rig {

namespace {
const char* const kSharedWorld = "--pose sim needs --camera sim: the simulated table and camera share one world";
}

CaptureRig::CaptureRig(const CaptureDevices& d) {
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

}  // namespace keyturn::rig
