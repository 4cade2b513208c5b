#include "keyturn/rig/simulated_rig.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "keyturn/drivers/modbus_turntable.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/mesh.h"

namespace fs = std::filesystem;

namespace keyturn::rig {

CameraSpec writeSimulatedCameraConfig(const std::string& path, const SimulatedCameraOptions& o) {
  if (const fs::path dir = fs::path(path).parent_path(); !dir.empty()) fs::create_directories(dir);
  sim::MesaSrSimConfig c;
  c.mesh = o.mesh.rfind("builtin:", 0) == 0 ? o.mesh : fs::absolute(o.mesh).string();
  c.elevation = o.elevation_deg;
  c.distance = o.distance;
  c.roll = o.roll_deg;
  c.scale = o.scale;
  c.seed = o.seed;
  c.faults.random_rate = o.fault_rate;
  c.frame_rate = o.frame_rate;
  c.noise_per_pose = o.noise_per_pose;
  c.world = o.world.empty() ? "" : fs::absolute(o.world).string();
  c.unplug_file = o.unplug_file;
  c.save(path);
  CameraSpec spec;
  spec.sim_config = path;
  return spec;
}

SimulatedTurntable::SimulatedTurntable(sim::TurntableServerOptions so, DeviceLog log) {
  server_ = std::make_unique<sim::TurntableServer>(so);
  drivers::ModbusOptions mo;
  mo.log = log ? std::move(log) : [](const std::string& l) { std::fprintf(stderr, "keyturn: turntable: %s\n", l.c_str()); };
  client_ = std::make_unique<drivers::ModbusTurntable>(drivers::ModbusEndpoint::parse(server_->endpoint()),
                                                       drivers::ModbusTurntableProfile::load("keyturn-sim"), mo);
}

SimulatedTurntable::~SimulatedTurntable() {
  client_.reset();  // the client goes first: it talks to the server
}

drivers::Pose SimulatedTurntable::read() { return client_->read(); }
void SimulatedTurntable::moveTo(double deg) { client_->moveTo(deg); }
void SimulatedTurntable::home() { client_->home(); }
void SimulatedTurntable::stop() { client_->stop(); }
std::string SimulatedTurntable::describe() const { return "simulated turntable, " + client_->describe(); }

sim::TurntableMotion captureMotion(bool fast) {
  sim::TurntableMotion m;
  m.max_speed_deg_s = fast ? 7200 : 720;
  m.max_accel_deg_s2 = fast ? 1.44e6 : 14400;
  m.settle_s = fast ? 0.0 : 0.005;
  m.jitter_deg = fast ? 0.0 : 0.01;
  return m;
}

std::string simulatedOpenNi2Uri(const std::string& config_path) {
  return "keyturn-sim://" + fs::absolute(config_path).lexically_normal().string();
}

SimulatedRig openSimulatedRig(const SimulatedRigOptions& o) {
  const SimulatedRigFiles files{o.dir};
  fs::create_directories(files.dir);
  SimulatedCameraOptions camera = o.camera;
  if (o.simulated_pose) camera.world = fs::absolute(files.world()).string();
  else camera.world = o.world;
  sim::TurntableServerOptions so;
  if (o.simulated_pose) {
    so.world_file = camera.world;
    so.motion = captureMotion(o.fast);
    so.seed = o.camera.seed;
    so.faults.random_rate = o.camera.fault_rate;
  }
  DeviceFactory factory(so);
  SimulatedRig rig;
  if (o.simulated_pose) rig.turntable = factory.openSimulatedTurntable();
  CameraSpec spec = writeSimulatedCameraConfig(files.cameraConfig(), camera);
  if (o.openni2) {
    const std::string config = spec.sim_config;
    spec = CameraSpec();
    spec.kind = CameraSpec::Kind::OpenNi2;
    spec.openni2_uri = simulatedOpenNi2Uri(config);
  }
  rig.camera = factory.openCamera(spec);
  rig.camera_from_turntable = *factory.cameraFromTurntable();
  return rig;
}

}  // namespace keyturn::rig
