#pragma once
// --pose sim|modbus-tcp:HOST:PORT|modbus-rtu:DEV → an open PoseSource. "sim"
// starts the simulated turntable in this process on loopback Modbus TCP (fast
// motion, so simulated captures run faster than real time) and the driver
// talks to it over the real protocol.
#include <memory>
#include <string>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/sim/turntable_sim.h"

namespace keyturn::app {

struct PoseChoice {
  std::unique_ptr<sim::TurntableServer> simulator;  // set for "sim"; outlives the driver below
  std::unique_ptr<drivers::PoseSource> source;
};

PoseChoice openPoseSource(const std::string& spec, const std::string& profile, const std::string& world_file);

}  // namespace keyturn::app
