#pragma once
// Reading a JSON file (or a JSON text with its source's name): the one reader of keyturn's JSON
// files (model sidecars, view sidecars, evaluation parts, camera files, Modbus profiles, CANopen
// axes, the simulator's configuration). What is wrong is one keyturn::Error line naming the file:
//   PATH: cannot read (No such file or directory)
//   PATH: empty file, expected JSON
//   PATH: not JSON at byte 14 (unexpected end of input; expected '}')
//   PATH: expected a JSON object, found an array
// What the JSON holds is the caller's to check (json_error.h words the library's errors there).
#include <nlohmann/json.hpp>
#include <string>

namespace keyturn {

// The kind of value a file must hold at its top.
enum class JsonShape { Any, Object, Array };

nlohmann::json readJsonFile(const std::string& path, JsonShape shape = JsonShape::Any);
// `text` as read from `source` (a path, or a built-in's name), with readJsonFile's messages.
nlohmann::json parseJson(const std::string& text, const std::string& source, JsonShape shape = JsonShape::Any);

}  // namespace keyturn
