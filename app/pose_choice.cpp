#include "pose_choice.h"

#include <cstdio>

#include "keyturn/core/error.h"
#include "keyturn/drivers/modbus_turntable.h"

namespace keyturn::app {

PoseChoice openPoseSource(const std::string& spec, const std::string& profile) {
  PoseChoice c;
  drivers::ModbusOptions o;
  o.log = [](const std::string& l) { std::fprintf(stderr, "keyturn: turntable: %s\n", l.c_str()); };
  if (spec.rfind("modbus-", 0) == 0) {
    c.source = std::make_unique<drivers::ModbusTurntable>(drivers::ModbusEndpoint::parse(spec),
                                                          drivers::ModbusTurntableProfile::load(profile), o);
    return c;
  }
  throw Error("--pose '" + spec + "': expected sim, modbus-tcp:HOST:PORT or modbus-rtu:DEVICE (CAN comes later)");
}

}  // namespace keyturn::app
