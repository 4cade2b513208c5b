#pragma once
// The device flags of grab, capture and turntable read into the rig's typed specs
// (rig/device_spec.h): --camera and --pose text, and the flags that fill a spec's
// fields when its text leaves them out (--mesasr-lib, --sim-config, --profile).
#include <string>

#include "keyturn/rig/device_spec.h"

namespace keyturn::app {

// library: for usb/eth (a spec's own ,lib= wins); sim_config: for sim (a spec's own sim:CONFIG wins).
rig::CameraSpec cameraSpec(const std::string& camera, const std::string& library, const std::string& sim_config);
// profile: for modbus and can (a spec's own ,profile= wins).
rig::PoseSpec poseSpec(const std::string& pose, const std::string& profile);

}  // namespace keyturn::app
