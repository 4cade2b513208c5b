#include "pose_choice.h"

#include <cstdio>

#include "keyturn/core/error.h"
#include "keyturn/drivers/modbus_turntable.h"

namespace keyturn::app {

PoseChoice openPoseSource(const std::string& spec, const std::string& profile, const std::string& world_file) {
  PoseChoice c;
  drivers::ModbusOptions o;
  o.log = [](const std::string& l) { std::fprintf(stderr, "keyturn: turntable: %s\n", l.c_str()); };
  if (spec == "sim") {
    sim::TurntableServerOptions so;
    so.world_file = world_file;
    so.motion.max_speed_deg_s = 720;
    so.motion.max_accel_deg_s2 = 14400;
    so.motion.settle_s = 0.005;
    c.simulator = std::make_unique<sim::TurntableServer>(so);
    c.source = std::make_unique<drivers::ModbusTurntable>(drivers::ModbusEndpoint::parse(c.simulator->endpoint()),
                                                          drivers::ModbusTurntableProfile::load("keyturn-sim"), o);
    return c;
  }
  if (spec.rfind("modbus-", 0) == 0) {
    c.source = std::make_unique<drivers::ModbusTurntable>(drivers::ModbusEndpoint::parse(spec),
                                                          drivers::ModbusTurntableProfile::load(profile), o);
    return c;
  }
  throw Error("--pose '" + spec + "': expected sim, modbus-tcp:HOST:PORT or modbus-rtu:DEVICE (CAN comes later)");
}

}  // namespace keyturn::app
