#pragma once
// --pose modbus-tcp:HOST:PORT|modbus-rtu:DEV|can:IFACE → an open PoseSource
// (for can: the profile argument names the CANopen axes file). The
// simulated turntable ("sim") is opened with the simulated camera (sim_rig.h).
#include <memory>
#include <string>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/sim/turntable_sim.h"

namespace keyturn::app {

struct PoseChoice {
  std::unique_ptr<sim::TurntableServer> simulator;  // set for "sim"; outlives the driver below
  std::unique_ptr<drivers::PoseSource> source;
};

PoseChoice openPoseSource(const std::string& spec, const std::string& profile);

}  // namespace keyturn::app
