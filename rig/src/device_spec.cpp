#include "keyturn/rig/device_spec.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "keyturn/core/error.h"
#include "keyturn/drivers/sr4000_camera.h"

namespace keyturn::rig {
namespace {

const char* const kCameraChoices =
    "expected sim, sim:CONFIG, usb, usb:SERIAL, eth:IP, openni2, openni2:URI, playback:DATASET[@FPS][@once] or "
    "playback:FILE.oni[@FPS][@once] (usb and eth take ,lib=LIBMESASR)";
const char* const kPoseChoices =
    "expected sim, playback, playback:DATASET, modbus-tcp:HOST:PORT[@UNIT], modbus-rtu:DEVICE[:BAUD[:8N1]][@UNIT] or "
    "can:IFACE (modbus and can take ,profile=FILE)";

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

bool isOniFile(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".oni") == 0;
}

std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

// "DATASET[@FPS][@once]": an '@' not followed by a rate or "once" stays in the folder's name.
PlaybackSpec parsePlayback(const std::string& what, const std::string& text, std::string_view form) {
  PlaybackSpec p;
  std::string rest = text;
  const std::string once = "@once";
  if (rest.size() > once.size() && rest.compare(rest.size() - once.size(), once.size(), once) == 0) {
    p.loop = false;
    rest.resize(rest.size() - once.size());
  }
  if (const std::size_t at = rest.rfind('@'); at != std::string::npos) {
    const std::string tail = rest.substr(at + 1);
    char* end = nullptr;
    const double fps = std::strtod(tail.c_str(), &end);
    if (!tail.empty() && end && *end == '\0') {
      if (!(fps > 0) || !std::isfinite(fps))
        throw Error(what + ": the playback rate after @ must be a positive number of frames/s");
      p.rate_fps = fps;
      rest.resize(at);
    }
  }
  if (rest.empty()) throw Error(what + ": playback needs a dataset folder (" + std::string(form) + ")");
  p.dataset = rest;
  return p;
}

std::string playbackText(const PlaybackSpec& p) {
  return p.dataset + (p.rate_fps > 0 ? "@" + number(p.rate_fps) : "") + (p.loop ? "" : "@once");
}

// Splits "ARGUMENT,key=value" at the first ',' (arguments that take options hold none) and checks the key.
std::string splitOption(const std::string& what, std::string& argument, const char* key, const char* choices) {
  const std::size_t comma = argument.find(',');
  if (comma == std::string::npos) return "";
  const std::string option = argument.substr(comma + 1);
  argument.resize(comma);
  const std::string prefix = std::string(key) + "=";
  if (!startsWith(option, prefix.c_str()) || option.size() == prefix.size())
    throw Error(what + ": unknown option '" + option + "'; " + choices);
  return option.substr(prefix.size());
}

std::string modbusText(const drivers::ModbusEndpoint& e) {
  std::string s;
  if (e.kind == drivers::ModbusEndpoint::Kind::Tcp) {
    s = "modbus-tcp:" + e.host + ":" + std::to_string(e.port);
  } else {
    s = "modbus-rtu:" + e.device + ":" + std::to_string(e.baud) + ":" + std::to_string(e.data_bits) + e.parity +
        std::to_string(e.stop_bits);
  }
  return e.unit_id == 1 ? s : s + "@" + std::to_string(e.unit_id);
}

bool sameEndpoint(const drivers::ModbusEndpoint& a, const drivers::ModbusEndpoint& b) {
  if (a.kind != b.kind || a.unit_id != b.unit_id) return false;
  if (a.kind == drivers::ModbusEndpoint::Kind::Tcp) return a.host == b.host && a.port == b.port;
  return a.device == b.device && a.baud == b.baud && a.parity == b.parity && a.data_bits == b.data_bits &&
         a.stop_bits == b.stop_bits;
}

}  // namespace

CameraSpec CameraSpec::parse(const std::string& text) {
  const std::string what = "camera '" + text + "'";
  CameraSpec s;
  if (text == "sim") return s;
  if (startsWith(text, "sim:")) {
    s.sim_config = text.substr(4);
    if (s.sim_config.empty()) throw Error(what + ": sim: needs the simulator's configuration file; " + kCameraChoices);
    return s;
  }
  if (startsWith(text, "playback:")) {
    s.kind = Kind::Playback;
    s.playback = parsePlayback(what, text.substr(9), "playback:DATASET[@FPS][@once]");
    if (isOniFile(s.playback.dataset)) s.kind = Kind::OniFile;  // OpenNI2's recording, not a dataset folder
    return s;
  }
  if (text == "openni2" || startsWith(text, "openni2:")) {
    s.kind = Kind::OpenNi2;
    if (text != "openni2") {
      s.openni2_uri = text.substr(8);
      if (s.openni2_uri.empty()) throw Error(what + ": openni2: needs the device's URI (keyturn devices lists them); " + kCameraChoices);
    }
    return s;
  }
  if (text == "usb" || startsWith(text, "usb:") || startsWith(text, "usb,") || startsWith(text, "eth:")) {
    std::string connection = text;
    s.mesasr_library = splitOption(what, connection, "lib", kCameraChoices);
    drivers::Sr4000Connection c;
    try {
      c = drivers::Sr4000Connection::parse(connection);
    } catch (const Error& e) {
      throw Error(std::string(e.what()) + "; " + kCameraChoices);
    }
    s.kind = c.kind == drivers::Sr4000Connection::Kind::Ethernet ? Kind::Ethernet : Kind::Usb;
    s.usb_serial = c.serial;
    s.address = c.address;
    return s;
  }
  throw Error(what + ": " + kCameraChoices);
}

std::string CameraSpec::toString() const {
  const std::string lib = mesasr_library.empty() ? "" : ",lib=" + mesasr_library;
  switch (kind) {
    case Kind::Simulated: return sim_config.empty() ? "sim" : "sim:" + sim_config;
    case Kind::Usb: return (usb_serial ? "usb:" + std::to_string(usb_serial) : std::string("usb")) + lib;
    case Kind::Ethernet: return "eth:" + address + lib;
    case Kind::Playback:
    case Kind::OniFile: return "playback:" + playbackText(playback);
    case Kind::OpenNi2: return openni2_uri.empty() ? "openni2" : "openni2:" + openni2_uri;
  }
  return "sim";
}

std::string CameraSpec::describe() const {
  switch (kind) {
    case Kind::Simulated: return sim_config.empty() ? "simulated SR4000" : "simulated SR4000 (" + sim_config + ")";
    case Kind::Usb: return usb_serial ? "SR4000 " + std::to_string(usb_serial) + " on USB" : "SR4000 on USB";
    case Kind::Ethernet: return "SR4000 at " + address;
    case Kind::Playback: return "recording " + playback.dataset;
    case Kind::OpenNi2: return openni2_uri.empty() ? "OpenNI2 camera" : "OpenNI2 camera " + openni2_uri;
    case Kind::OniFile: return "OpenNI2 recording " + playback.dataset;
  }
  return "camera";
}

bool CameraSpec::operator==(const CameraSpec& o) const {
  return kind == o.kind && sim_config == o.sim_config && usb_serial == o.usb_serial && address == o.address &&
         mesasr_library == o.mesasr_library && playback == o.playback && openni2_uri == o.openni2_uri;
}

PoseSpec PoseSpec::parse(const std::string& text) {
  const std::string what = "pose '" + text + "'";
  PoseSpec s;
  if (text == "sim") return s;
  if (text == "playback" || startsWith(text, "playback:")) {
    s.kind = Kind::Playback;
    if (text != "playback") s.playback = parsePlayback(what, text.substr(9), "playback[:DATASET[@FPS][@once]]");
    return s;
  }
  if (startsWith(text, "modbus-tcp:") || startsWith(text, "modbus-rtu:")) {
    std::string endpoint = text;
    s.profile = splitOption(what, endpoint, "profile", kPoseChoices);
    try {
      s.modbus = drivers::ModbusEndpoint::parse(endpoint);
    } catch (const Error& e) {
      throw Error(std::string(e.what()) + "; " + kPoseChoices);
    }
    s.kind = s.modbus.kind == drivers::ModbusEndpoint::Kind::Tcp ? Kind::ModbusTcp : Kind::ModbusRtu;
    return s;
  }
  if (startsWith(text, "can:")) {
    std::string iface = text.substr(4);
    s.profile = splitOption(what, iface, "profile", kPoseChoices);
    if (iface.empty()) throw Error(what + ": can: needs the CAN interface; " + kPoseChoices);
    s.kind = Kind::Can;
    s.can_interface = iface;
    return s;
  }
  throw Error(what + ": " + kPoseChoices);
}

std::string PoseSpec::toString() const {
  const std::string profile_option = profile.empty() ? "" : ",profile=" + profile;
  switch (kind) {
    case Kind::Simulated: return "sim";
    case Kind::Playback: return playback.dataset.empty() ? "playback" : "playback:" + playbackText(playback);
    case Kind::ModbusTcp:
    case Kind::ModbusRtu: return modbusText(modbus) + profile_option;
    case Kind::Can: return "can:" + can_interface + profile_option;
  }
  return "sim";
}

std::string PoseSpec::describe() const {
  switch (kind) {
    case Kind::Simulated: return "simulated turntable";
    case Kind::Playback:
      return playback.dataset.empty() ? "poses of the recording" : "poses of the recording " + playback.dataset;
    case Kind::ModbusTcp: return "Modbus TCP turntable at " + modbus.host + ":" + std::to_string(modbus.port);
    case Kind::ModbusRtu: return "Modbus RTU turntable on " + modbus.device;
    case Kind::Can: return "CANopen axes on " + can_interface;
  }
  return "pose source";
}

bool PoseSpec::operator==(const PoseSpec& o) const {
  if (kind != o.kind || profile != o.profile || can_interface != o.can_interface || !(playback == o.playback))
    return false;
  return (kind != Kind::ModbusTcp && kind != Kind::ModbusRtu) || sameEndpoint(modbus, o.modbus);
}

}  // namespace keyturn::rig
