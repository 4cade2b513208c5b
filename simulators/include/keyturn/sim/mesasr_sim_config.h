#pragma once
// Configuration of libmesasr-sim, the simulated libMesaSR (and of the simulated
// OpenNI2 driver, simulators/openni2_sim/, which reads the same file): a JSON file read when
// a camera is opened, passed by keyturn through KTSIM_OpenWithConfig
// (drivers/mesasr_api.h) and named by $MESASR_SIM_CONFIG for programs outside
// keyturn (SR_OpenUSB/SR_OpenETH). Everything is optional.
//
// {
//   "mesh": "builtin:mug" | "path/to/object.ply",   (relative to the config file)
//   "distance": 0,             camera to object centre, m; 0 = operator placement
//   "elevation": 30,           degrees
//   "turntable_deg": 0,        object rotation when no world file is given
//   "world": "world.json",     shared world state: {"turntable_deg": A} read at every acquire
//   "serial": 4000123, "seed": 1,
//   "unplug_file": "",         while this file exists the camera is unplugged: opens fail, acquires fail
//   "frame_rate": 0,           frames/s SR_Acquire keeps to, as a real camera does; 0 = as fast as it renders
//   "noise_per_pose": false,   one noise draw per turntable angle (frames at a still pose are equal), else one per frame
//   "faults": { "open_fail": false,      every open returns -1
//               "timeout_every": 0,      every Nth acquire times out (returns -1)
//               "corrupt_every": 0,      every Nth acquire transfers a short frame
//               "disconnect_after": 0,   after N frames the camera stops answering until reopened
//               "random_rate": 0 }       each acquire: a random one of those faults with this probability (seeded)
// }
#include <cstdint>
#include <string>

namespace keyturn::sim {

struct MesaSrSimFaults {
  bool open_fail = false;
  int timeout_every = 0;
  int corrupt_every = 0;
  int disconnect_after = 0;
  double random_rate = 0;  // each acquire fails with this probability: timeout, short frame or disconnect
};

struct MesaSrSimConfig {
  std::string mesh = "builtin:mug";
  double distance = 0.0;
  double elevation = 30.0;
  double turntable_deg = 0.0;
  double roll = 0.0;  // degrees about the optical axis
  double scale = 1.0;  // the mesh grown by this factor (sim::scaledMesh)
  std::string world;
  std::uint32_t serial = 4000123;
  std::uint64_t seed = 1;
  double frame_rate = 0.0;
  // The simulated OpenNI2 driver: the same noise in every frame at one turntable angle. Its frames
  // run free at 30/s, so which frame a capture takes depends on timing; with this on, a simulated
  // dataset is the same on every run (keyturn simulate sets it). Off: new noise every frame.
  bool noise_per_pose = false;
  // The noise seed of a frame at this turntable angle when noise_per_pose is set: the same for
  // every frame at the angle, for both simulated cameras.
  std::uint64_t poseNoiseSeed(double turntable_deg) const;
  std::string unplug_file;
  MesaSrSimFaults faults;

  // From the file the environment variable names (libmesasr-sim: MESASR_SIM_CONFIG; the
  // simulated OpenNI2 driver: KEYTURN_OPENNI2_SIM_CONFIG), or defaults when unset. Throws keyturn::Error.
  static MesaSrSimConfig fromEnvironment(const char* variable = "MESASR_SIM_CONFIG");
  static MesaSrSimConfig fromFile(const std::string& path);
  void save(const std::string& path) const;
};

// The shared simulated world: the turntable angle the simulated rig reports
// and the simulated camera renders. Written atomically (temp + rename).
double readWorldTurntable(const std::string& path, double fallback);
void writeWorldTurntable(const std::string& path, double degrees);

}  // namespace keyturn::sim
