#include "device_options.h"

namespace keyturn::app {

rig::CameraSpec cameraSpec(const std::string& camera, const std::string& library, const std::string& sim_config) {
  rig::CameraSpec spec = rig::CameraSpec::parse(camera);
  const bool sr4000 = spec.kind == rig::CameraSpec::Kind::Usb || spec.kind == rig::CameraSpec::Kind::Ethernet;
  if (sr4000 && spec.mesasr_library.empty()) spec.mesasr_library = library;
  if (spec.kind == rig::CameraSpec::Kind::Simulated && spec.sim_config.empty()) spec.sim_config = sim_config;
  return spec;
}

rig::PoseSpec poseSpec(const std::string& pose, const std::string& profile) {
  rig::PoseSpec spec = rig::PoseSpec::parse(pose);
  const bool profiled = spec.kind == rig::PoseSpec::Kind::ModbusTcp || spec.kind == rig::PoseSpec::Kind::ModbusRtu ||
                        spec.kind == rig::PoseSpec::Kind::Can;
  if (profiled && spec.profile.empty()) spec.profile = profile;
  return spec;
}

}  // namespace keyturn::app
