#include "keyturn/studio/rig_factory.h"

namespace keyturn::studio {

std::string CameraRequest::describe() const {
  switch (kind) {
    case Kind::Simulated: return "simulated SR4000 (" + sim_object + ")";
    case Kind::Usb: return usb_serial ? "SR4000 " + std::to_string(usb_serial) + " on USB" : "SR4000 on USB";
    case Kind::Ethernet: return "SR4000 at " + address;
    case Kind::Playback: return "recording " + playback.dataset;
  }
  return "camera";
}

std::string PoseRequest::describe() const {
  switch (kind) {
    case Kind::None: return "no pose source";
    case Kind::Simulated: return "simulated turntable";
    case Kind::ModbusTcp: return "Modbus TCP turntable at " + endpoint;
    case Kind::ModbusRtu: return "Modbus RTU turntable on " + endpoint;
    case Kind::Can: return "CANopen axes on " + endpoint;
    case Kind::Playback: return "poses of the recording " + playback.dataset;
  }
  return "pose source";
}

}  // namespace keyturn::studio
