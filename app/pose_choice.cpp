#include "pose_choice.h"

#include <cstdio>

#include "keyturn/core/error.h"
#include "keyturn/drivers/canopen_pose.h"
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
  if (spec.rfind("can:", 0) == 0) {
    // CANopen axes over SocketCAN; the axes file takes the profile's place.
    if (profile.empty() || profile == "keyturn-sim")
      throw Error("--pose " + spec + " needs --profile AXES.json (the CANopen nodes: see docs/protocols.md)");
    c.source = std::make_unique<drivers::CanOpenPoseSource>(std::make_unique<drivers::SocketCanBus>(spec.substr(4)),
                                                            drivers::CanOpenAxis::loadAll(profile));
    return c;
  }
  throw Error("--pose '" + spec + "': expected sim, modbus-tcp:HOST:PORT, modbus-rtu:DEVICE or can:IFACE");
}

}  // namespace keyturn::app
