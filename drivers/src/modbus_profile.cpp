#include "keyturn/drivers/modbus_profile.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "keyturn/core/error.h"
#include "keyturn/core/json_file.h"
#include "keyturn/core/json_integer.h"

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
  r.bits = jsonInteger(j, "bits", 16, 16, 32, where);
  if (r.bits != 16 && r.bits != 32) throw Error(where + ": bits must be 16 or 32");
  r.address = jsonInteger(j, "address", 0, 65535 - (r.bits / 16 - 1), where);
  const std::string wo = j.value("word_order", "high_first");
  if (wo != "high_first" && wo != "low_first") throw Error(where + ": word_order must be high_first or low_first");
  r.high_word_first = wo == "high_first";
  r.is_signed = j.value("signed", false);
  return r;
}

// A register write: address and 16-bit value.
ModbusWrite parseWrite(const nlohmann::json& j, const std::string& where) {
  return {jsonInteger(j, "address", 0, 65535, where), jsonInteger(j, "value", 0, 65535, where)};
}

// Status bits of a 16-bit register: a bit number past 15 would shift out of range.
ModbusStatus parseStatus(const nlohmann::json& j, const std::string& where) {
  return {jsonInteger(j, "address", 0, 65535, where), jsonInteger(j, "moving_bit", 0, 0, 15, where),
          jsonInteger(j, "in_position_bit", 1, 0, 15, where)};
}

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
  const nlohmann::json j = parseJson(text, source, JsonShape::Object);
  ModbusTurntableProfile p;
  try {
    p.name = j.value("name", source);
    p.position = parseRegister(j.at("position"), source + ": position");
    p.counts_per_revolution = j.at("counts_per_revolution").get<double>();
    p.zero_offset_deg = j.value("zero_offset_deg", 0.0);
    p.direction = jsonInteger(j, "direction", 1, std::numeric_limits<int>::min(), std::numeric_limits<int>::max(), source);
    if (j.contains("commands")) {
      const auto& c = j.at("commands");
      if (c.contains("target")) p.target = parseRegister(c.at("target"), source + ": commands.target");
      if (c.contains("start")) p.start = parseWrite(c.at("start"), source + ": commands.start");
      if (c.contains("home")) p.home = parseWrite(c.at("home"), source + ": commands.home");
      if (c.contains("stop")) p.stop = parseWrite(c.at("stop"), source + ": commands.stop");
      if (c.contains("status")) p.status = parseStatus(c.at("status"), source + ": commands.status");
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(source + ": bad Modbus profile: " + e.what());
  }
  // Bounded so that a target in counts fits the 32-bit register it is written to.
  if (!(p.counts_per_revolution > 0 && p.counts_per_revolution <= 4294967296.0))
    throw Error(source + ": counts_per_revolution must be in (0, 2^32]");
  if (!(std::abs(p.zero_offset_deg) <= 360)) throw Error(source + ": zero_offset_deg must be in -360..360");
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
