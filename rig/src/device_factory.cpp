#include "keyturn/rig/device_factory.h"

#include <arpa/inet.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "keyturn/core/error.h"
#include "keyturn/core/install_layout.h"
#include "keyturn/drivers/canopen_pose.h"
#include "keyturn/drivers/modbus_turntable.h"
#include "keyturn/drivers/openni2_camera.h"
#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/rig/dataset_playback.h"
#include "keyturn/rig/simulated_rig.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/structured_light_view.h"
#include "keyturn/sim/tof_view.h"


namespace keyturn::rig {

std::string simulatorLibraryPath() {
  const char* env = std::getenv("KEYTURN_MESASR_SIM");
  return env && *env ? env : prefixPath("lib/keyturn/mesasr-sim/libmesasr.so").string();
}

namespace {

DeviceLog orStderr(DeviceLog log, const char* device) {
  if (log) return log;
  return [device](const std::string& line) { std::fprintf(stderr, "keyturn: %s: %s\n", device, line.c_str()); };
}

// The simulator can only say "open returned -1": its configuration and mesh are read here first, so a
// bad file is named. Paths in the configuration are relative to its folder.
Eigen::Matrix4d simulatedCameraFromTurntable(const CameraSpec& spec) {
  const sim::MesaSrSimConfig c =
      spec.sim_config.empty() ? sim::MesaSrSimConfig() : sim::MesaSrSimConfig::fromFile(spec.sim_config);
  sim::Mesh mesh;
  try {
    mesh = sim::scaledMesh(sim::loadMeshOrBuiltin(c.mesh), c.scale);
  } catch (const Error& e) {
    throw Error((spec.sim_config.empty() ? std::string("simulated SR4000") : spec.sim_config) + ": mesh: " + e.what());
  }
  sim::SceneView view;
  view.distance = c.distance;
  view.elevation_deg = c.elevation;
  view.roll_deg = c.roll;
  return sim::cameraFromTurntable(mesh, view);
}

// The simulated OpenNI2 driver's camera (keyturn-sim:///CONFIG) stands where an operator would stand a
// Kinect-class camera, unless its configuration gives the distance; anything else is a real device.
std::optional<Eigen::Matrix4d> simulatedOpenNi2CameraFromTurntable(const CameraSpec& spec) {
  const std::string scheme = "keyturn-sim://";
  if (spec.openni2_uri.rfind(scheme, 0) != 0 || spec.openni2_uri.size() <= scheme.size() ||
      spec.openni2_uri[scheme.size()] != '/')
    return std::nullopt;
  const std::string config = spec.openni2_uri.substr(scheme.size());
  const sim::MesaSrSimConfig c = sim::MesaSrSimConfig::fromFile(config);
  sim::Mesh mesh;
  try {
    mesh = sim::scaledMesh(sim::loadMeshOrBuiltin(c.mesh), c.scale);
  } catch (const Error& e) {
    throw Error(config + ": mesh: " + e.what());
  }
  const sim::Intrinsics k = sim::kinectIntrinsics();
  sim::SceneView view;
  view.distance = c.distance > 0 ? c.distance : sim::structuredLightOperatorDistance(mesh, k, sim::StructuredLightModel());
  view.elevation_deg = c.elevation;
  view.roll_deg = c.roll;
  return sim::cameraFromTurntable(mesh, view, k);
}

drivers::Sr4000Connection connectionOf(const CameraSpec& spec) {
  drivers::Sr4000Connection c;
  if (spec.kind == CameraSpec::Kind::Simulated) {
    c.kind = drivers::Sr4000Connection::Kind::Simulator;
    c.simulator_config = spec.sim_config;
  } else if (spec.kind == CameraSpec::Kind::Ethernet) {
    in_addr addr{};
    if (::inet_pton(AF_INET, spec.address.c_str(), &addr) != 1)
      throw Error("camera '" + spec.toString() + "': expected eth:IPv4-ADDRESS");
    c.kind = drivers::Sr4000Connection::Kind::Ethernet;
    c.address = spec.address;
  } else {
    c.serial = spec.usb_serial;
  }
  return c;
}

}  // namespace

DeviceFactory::DeviceFactory(sim::TurntableServerOptions simulated_turntable)
    : simulated_turntable_(std::move(simulated_turntable)) {}

DeviceFactory::~DeviceFactory() = default;

std::unique_ptr<drivers::TofCamera> DeviceFactory::openCamera(const CameraSpec& spec, DeviceLog log) {
  if (spec.kind == CameraSpec::Kind::Playback) {
    auto played = recording(spec.playback);
    if (played->ended()) played->rewind();  // opened again after the end: plays again (the pose follows)
    std::lock_guard<std::mutex> l(mutex_);
    camera_from_turntable_ = played->cameraFromTurntable();  // the recorded calibration
    return std::make_unique<PlaybackCamera>(played);
  }
  if (spec.kind == CameraSpec::Kind::OpenNi2 || spec.kind == CameraSpec::Kind::OniFile) {
    drivers::OpenNi2Options o;
    o.log = orStderr(std::move(log), "camera");
    if (spec.kind == CameraSpec::Kind::OniFile) {
      o.oni_file = spec.playback.dataset;
      o.playback_fps = spec.playback.rate_fps;
      o.loop = spec.playback.loop;
    } else {
      o.uri = spec.openni2_uri;
    }
    const std::optional<Eigen::Matrix4d> pose =
        spec.kind == CameraSpec::Kind::OpenNi2 ? simulatedOpenNi2CameraFromTurntable(spec) : std::nullopt;
    auto camera = std::make_unique<drivers::OpenNi2Camera>(o);
    std::lock_guard<std::mutex> l(mutex_);
    camera_from_turntable_ = pose;  // a real rig's comes from an axis calibration
    return camera;
  }
  drivers::Sr4000Options options;
  options.log = orStderr(std::move(log), "camera");
  const drivers::Sr4000Connection connection = connectionOf(spec);  // validated before any library loads
  std::optional<Eigen::Matrix4d> pose;
  std::shared_ptr<drivers::MesaSrLibrary> library;
  if (spec.kind == CameraSpec::Kind::Simulated) {
    pose = simulatedCameraFromTurntable(spec);
    options.name = "simulated SR4000";
    library = drivers::MesaSrLibrary::load(simulatorLibraryPath());
  } else {
    library = drivers::MesaSrLibrary::load(spec.mesasr_library);
  }
  auto camera = std::make_unique<drivers::Sr4000Camera>(std::move(library), connection, options);
  std::lock_guard<std::mutex> l(mutex_);
  camera_from_turntable_ = pose;  // a real rig: none until an axis calibration supplies it
  return camera;
}

std::unique_ptr<SimulatedTurntable> DeviceFactory::openSimulatedTurntable(DeviceLog log) {
  if (simulated_turntable_.world_file.empty())
    throw Error("pose 'sim': the simulated turntable shares the simulated camera's world, and none was set up here");
  return std::make_unique<SimulatedTurntable>(simulated_turntable_, orStderr(std::move(log), "turntable"));
}

std::unique_ptr<drivers::PoseSource> DeviceFactory::openPoseSource(const PoseSpec& spec, DeviceLog log) {
  switch (spec.kind) {
    case PoseSpec::Kind::Simulated: return openSimulatedTurntable(std::move(log));
    case PoseSpec::Kind::Playback: {
      if (!spec.playback.dataset.empty()) return std::make_unique<PlaybackPose>(recording(spec.playback));
      std::lock_guard<std::mutex> l(mutex_);
      if (!recording_) throw Error("pose 'playback' needs camera playback:DATASET (the recording holds both)");
      return std::make_unique<PlaybackPose>(recording_);
    }
    case PoseSpec::Kind::ModbusTcp:
    case PoseSpec::Kind::ModbusRtu: {
      drivers::ModbusOptions o;
      o.log = orStderr(std::move(log), "turntable");
      return std::make_unique<drivers::ModbusTurntable>(
          spec.modbus, drivers::ModbusTurntableProfile::load(spec.profile.empty() ? "keyturn-sim" : spec.profile), o);
    }
    case PoseSpec::Kind::Can:
      // CANopen axes over SocketCAN; the axes file takes the register profile's place.
      if (spec.profile.empty() || spec.profile == "keyturn-sim")
        throw Error("pose '" + spec.toString() +
                    "' needs the CANopen axes file as its profile (can:IFACE,profile=AXES.json; see "
                    "docs/protocols.md)");
      return std::make_unique<drivers::CanOpenPoseSource>(std::make_unique<drivers::SocketCanBus>(spec.can_interface),
                                                          drivers::CanOpenAxis::loadAll(spec.profile));
  }
  throw Error("pose '" + spec.toString() + "': unknown kind");
}

std::optional<Eigen::Matrix4d> DeviceFactory::cameraFromTurntable() const {
  std::lock_guard<std::mutex> l(mutex_);
  return camera_from_turntable_;
}

std::shared_ptr<Recording> DeviceFactory::recording(const PlaybackSpec& spec) {
  std::lock_guard<std::mutex> l(mutex_);
  if (!recording_ || !(playing_ == spec)) {
    recording_ = std::make_shared<Recording>(spec.dataset, PlaybackOptions{spec.rate_fps, spec.loop});
    playing_ = spec;
  }
  return recording_;
}

}  // namespace keyturn::rig
