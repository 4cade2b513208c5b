#include "keyturn/rig/devices.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "keyturn/core/error.h"
#include "keyturn/core/install_layout.h"
#include "keyturn/drivers/canopen_pose.h"
#include "keyturn/drivers/modbus_turntable.h"
#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/rig/dataset_playback.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/mesh.h"


namespace keyturn::rig {

std::string simulatorLibraryPath() {
  const char* env = std::getenv("KEYTURN_MESASR_SIM");
  return env && *env ? env : prefixPath("lib/keyturn/mesasr-sim/libmesasr.so").string();
}

drivers::Sr4000Connection parseCameraSpec(const std::string& spec) {
  if (spec != "usb" && spec.rfind("usb:", 0) != 0 && spec.rfind("eth:", 0) != 0)
    throw Error("camera '" + spec + "': expected sim, usb, usb:SERIAL, eth:IP or playback:DATASET");
  return drivers::Sr4000Connection::parse(spec);
}

std::unique_ptr<drivers::TofCamera> openCamera(const std::string& spec, const std::string& sim_config,
                                               const std::string& library, DeviceLog log) {
  if (isPlaybackSpec(spec))
    return std::make_unique<PlaybackCamera>(std::make_shared<Recording>(playbackDataset(spec), playbackOptions(spec)));
  drivers::Sr4000Options options;
  options.log = log ? std::move(log) : [](const std::string& line) { std::cerr << "keyturn: camera: " << line << "\n"; };
  if (spec == "sim") {
    if (!sim_config.empty()) ::setenv("MESASR_SIM_CONFIG", sim_config.c_str(), 1);
    // The simulator can only say "open returned -1": read its configuration and mesh here first, so
    // a bad file is named. Paths in the configuration are relative to its folder.
    const sim::MesaSrSimConfig config = sim::MesaSrSimConfig::fromEnvironment();
    const char* config_path = std::getenv("MESASR_SIM_CONFIG");
    try {
      (void)sim::loadMeshOrBuiltin(config.mesh);
    } catch (const Error& e) {
      throw Error(std::string(config_path && *config_path ? config_path : "simulated SR4000") + ": mesh: " + e.what());
    }
    options.name = "simulated SR4000";
    return std::make_unique<drivers::Sr4000Camera>(drivers::MesaSrLibrary::load(simulatorLibraryPath()),
                                                   drivers::Sr4000Connection::parse("usb"), options);
  }
  const auto connection = parseCameraSpec(spec);  // validate before loading
  return std::make_unique<drivers::Sr4000Camera>(drivers::MesaSrLibrary::load(library), connection, options);
}

std::unique_ptr<drivers::PoseSource> openPoseSource(const std::string& spec, const std::string& profile,
                                                    DeviceLog log) {
  drivers::ModbusOptions o;
  o.log = log ? std::move(log) : [](const std::string& l) { std::fprintf(stderr, "keyturn: turntable: %s\n", l.c_str()); };
  if (spec.rfind("modbus-", 0) == 0)
    return std::make_unique<drivers::ModbusTurntable>(drivers::ModbusEndpoint::parse(spec),
                                                      drivers::ModbusTurntableProfile::load(profile), o);
  if (spec.rfind("can:", 0) == 0) {
    // CANopen axes over SocketCAN; the axes file takes the profile's place.
    if (profile.empty() || profile == "keyturn-sim")
      throw Error("--pose " + spec + " needs --profile AXES.json (the CANopen nodes: see docs/protocols.md)");
    return std::make_unique<drivers::CanOpenPoseSource>(std::make_unique<drivers::SocketCanBus>(spec.substr(4)),
                                                        drivers::CanOpenAxis::loadAll(profile));
  }
  throw Error("--pose '" + spec + "': expected sim, modbus-tcp:HOST:PORT, modbus-rtu:DEVICE or can:IFACE");
}

}  // namespace keyturn::rig
