#include "keyturn/drivers/modbus_profile.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "keyturn/core/error.h"

namespace keyturn::drivers {
namespace {

const char* kGenericEncoder = R"({
  "name": "generic-encoder",
  "position": {"function": "holding", "address": 0, "bits": 32, "word_order": "high_first", "signed": false},
  "counts_per_revolution": 4096, "zero_offset_deg": 0, "direction": 1
})";

const char* kKeyturnSim = R"({
  "name": "keyturn-sim",
  "position": {"function": "holding", "address": 0, "bits": 32, "word_order": "high_first", "signed": false},
  "counts_per_revolution": 36000, "zero_offset_deg": 0, "direction": 1,
  "commands": {
    "target": {"address": 10, "bits": 32, "word_order": "high_first", "signed": false},
    "start": {"address": 12, "value": 1},
    "home": {"address": 12, "value": 2},
    "stop": {"address": 12, "value": 3},
    "status": {"address": 2, "moving_bit": 0, "in_position_bit": 1}
  }
})";

ModbusRegister parseRegister(const nlohmann::json& j, const std::string& where) {
  ModbusRegister r;
  const std::string fn = j.value("function", "holding");
  if (fn == "holding") r.function = ModbusRegister::Function::Holding;
  else if (fn == "input") r.function = ModbusRegister::Function::Input;
  else throw Error(where + ": function must be holding or input, not '" + fn + "'");
  r.address = j.at("address").get<int>();
  r.bits = j.value("bits", 16);
  if (r.bits != 16 && r.bits != 32) throw Error(where + ": bits must be 16 or 32");
  const std::string wo = j.value("word_order", "high_first");
  if (wo != "high_first" && wo != "low_first") throw Error(where + ": word_order must be high_first or low_first");
  r.high_word_first = wo == "high_first";
  r.is_signed = j.value("signed", false);
  if (r.address < 0 || r.address > 65535 - (r.bits / 16 - 1)) throw Error(where + ": address out of 0..65535");
  return r;
}

ModbusWrite parseWrite(const nlohmann::json& j) { return {j.at("address").get<int>(), j.at("value").get<int>()}; }

}  // namespace

double ModbusTurntableProfile::countsToDegrees(double counts) const {
  const double deg = direction * counts / counts_per_revolution * 360.0 - zero_offset_deg;
  const double w = std::fmod(deg, 360.0);
  return w < 0 ? w + 360.0 : w;
}

double ModbusTurntableProfile::degreesToCounts(double degrees) const {
  return (degrees + zero_offset_deg) / 360.0 * counts_per_revolution * direction;
}

ModbusTurntableProfile ModbusTurntableProfile::fromJson(const std::string& text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw Error(source + ": not valid JSON: " + e.what());
  }
  ModbusTurntableProfile p;
  try {
    p.name = j.value("name", source);
    p.position = parseRegister(j.at("position"), source + ": position");
    p.counts_per_revolution = j.at("counts_per_revolution").get<double>();
    p.zero_offset_deg = j.value("zero_offset_deg", 0.0);
    p.direction = j.value("direction", 1);
    if (j.contains("commands")) {
      const auto& c = j.at("commands");
      if (c.contains("target")) p.target = parseRegister(c.at("target"), source + ": commands.target");
      if (c.contains("start")) p.start = parseWrite(c.at("start"));
      if (c.contains("home")) p.home = parseWrite(c.at("home"));
      if (c.contains("stop")) p.stop = parseWrite(c.at("stop"));
      if (c.contains("status")) {
        const auto& s = c.at("status");
        p.status = ModbusStatus{s.at("address").get<int>(), s.value("moving_bit", 0), s.value("in_position_bit", 1)};
      }
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(source + ": bad Modbus profile: " + e.what());
  }
  if (!(p.counts_per_revolution > 0)) throw Error(source + ": counts_per_revolution must be positive");
  if (p.direction != 1 && p.direction != -1) throw Error(source + ": direction must be 1 or -1");
  return p;
}

ModbusTurntableProfile ModbusTurntableProfile::load(const std::string& path_or_name) {
  if (path_or_name == "generic-encoder") return fromJson(kGenericEncoder, "generic-encoder");
  if (path_or_name == "keyturn-sim") return fromJson(kKeyturnSim, "keyturn-sim");
  std::ifstream in(path_or_name);
  if (!in) throw Error(path_or_name + ": no such Modbus profile (nor a built-in: generic-encoder, keyturn-sim)");
  std::stringstream ss;
  ss << in.rdbuf();
  return fromJson(ss.str(), path_or_name);
}

}  // namespace keyturn::drivers
