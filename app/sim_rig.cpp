#include "sim_rig.h"

#include <filesystem>

#include "camera_choice.h"
#include "keyturn/drivers/modbus_turntable.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/tof_view.h"

namespace fs = std::filesystem;

namespace keyturn::app {

SimRig openSimRig(const SimRigOptions& o) {
  SimRig rig;
  const std::string dir = o.dataset_root + "/.sim";
  fs::create_directories(dir);
  const std::string world = fs::absolute(dir + "/world.json").string();
  sim::MesaSrSimConfig c;
  c.mesh = o.mesh.rfind("builtin:", 0) == 0 ? o.mesh : fs::absolute(o.mesh).string();
  c.elevation = o.elevation_deg;
  c.distance = o.distance;
  c.seed = o.seed;
  c.faults.random_rate = o.fault_rate;
  if (o.simulated_pose) c.world = world;
  else if (!o.world.empty()) c.world = fs::absolute(o.world).string();
  const std::string config = dir + "/camera.json";
  c.save(config);

  const sim::Mesh mesh = sim::loadMeshOrBuiltin(c.mesh);
  sim::SceneView view;
  view.distance = o.distance;
  view.elevation_deg = o.elevation_deg;
  rig.camera_from_turntable = sim::cameraFromTurntable(mesh, view);

  if (o.simulated_pose) {
    sim::TurntableServerOptions so;
    so.world_file = world;
    so.motion.max_speed_deg_s = o.fast ? 7200 : 720;
    so.motion.max_accel_deg_s2 = o.fast ? 1.44e6 : 14400;
    so.motion.settle_s = o.fast ? 0.0 : 0.005;
    so.motion.jitter_deg = o.fast ? 0.0 : 0.01;
    so.seed = o.seed;
    so.faults.random_rate = o.fault_rate;
    rig.pose.simulator = std::make_unique<sim::TurntableServer>(so);
    drivers::ModbusOptions mo;
    mo.log = [](const std::string& l) { std::fprintf(stderr, "keyturn: turntable: %s\n", l.c_str()); };
    rig.pose.source = std::make_unique<drivers::ModbusTurntable>(
        drivers::ModbusEndpoint::parse(rig.pose.simulator->endpoint()),
        drivers::ModbusTurntableProfile::load("keyturn-sim"), mo);
  }
  rig.camera = openCamera("sim", config);
  return rig;
}

}  // namespace keyturn::app
