#pragma once
// The register map of a Modbus turntable or encoder, from a small JSON file:
//
// { "name": "generic-encoder",
//   "position": { "function": "holding"|"input", "address": 0, "bits": 32,
//                 "word_order": "high_first"|"low_first", "signed": false },
//   "counts_per_revolution": 4096, "zero_offset_deg": 0, "direction": 1,
//   "commands": {                                   (optional: a motorised table)
//     "target":  { "address": 10, "bits": 32, "word_order": "high_first", "signed": false },
//     "start":   { "address": 12, "value": 1 },
//     "home":    { "address": 12, "value": 2 },
//     "stop":    { "address": 12, "value": 3 },
//     "status":  { "address": 2, "moving_bit": 0, "in_position_bit": 1 } } }
#include <optional>
#include <string>

namespace keyturn::drivers {

struct ModbusRegister {
  enum class Function { Holding, Input } function = Function::Holding;
  int address = 0;
  int bits = 16;               // 16 or 32
  bool high_word_first = true;
  bool is_signed = false;
};

struct ModbusWrite {
  int address = 0;
  int value = 0;
};

struct ModbusStatus {
  int address = 0;
  int moving_bit = 0;
  int in_position_bit = 1;
};

struct ModbusTurntableProfile {
  std::string name;
  ModbusRegister position;
  double counts_per_revolution = 4096;
  double zero_offset_deg = 0;
  int direction = 1;  // +1 or -1
  std::optional<ModbusRegister> target;
  std::optional<ModbusWrite> start, home, stop;
  std::optional<ModbusStatus> status;

  bool motorised() const { return target && start; }
  double countsToDegrees(double counts) const;  // wrapped to [0, 360)
  double degreesToCounts(double degrees) const;

  // A file path, or a built-in name: "generic-encoder" (common RS485 absolute
  // encoders: 32-bit multi-turn count at 0–1, turns at 2, single-turn value at
  // 3, set zero at 8, direction at 9) or "keyturn-sim" (the simulated table).
  static ModbusTurntableProfile load(const std::string& path_or_name);
  static ModbusTurntableProfile fromJson(const std::string& json_text, const std::string& source);
};

}  // namespace keyturn::drivers
