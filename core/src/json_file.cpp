#include "keyturn/core/json_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "file_error.h"
#include "keyturn/core/json_error.h"

namespace keyturn {
namespace {

// nlohmann's parse error without its place ("parse error at line 1, column 5: "), which the byte
// says, and without "syntax error while parsing value - ", which every such error says.
std::string parseReason(const nlohmann::json::parse_error& e) {
  std::string s = jsonErrorText(e);
  if (s.rfind("parse error", 0) == 0) {
    const auto colon = s.find(": ");
    if (colon != std::string::npos) s.erase(0, colon + 2);
  }
  if (s.rfind("syntax error while parsing ", 0) == 0) {
    const auto dash = s.find(" - ");
    if (dash != std::string::npos) s.erase(0, dash + 3);
  }
  return s;
}

std::string withArticle(const nlohmann::json& j) {
  if (j.is_null()) return "null";
  const std::string type = j.type_name();
  return (type == "array" || type == "object" ? "an " : "a ") + type;
}

}  // namespace

nlohmann::json parseJson(const std::string& text, const std::string& source, JsonShape shape) {
  if (text.empty()) detail::fail(source, "empty file, expected JSON");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann counts the end of the input as one more byte read: a file cut short ends at its size.
    const std::size_t byte = std::min<std::size_t>(e.byte, text.size());
    detail::fail(source, "not JSON at byte " + std::to_string(byte) + " (" + parseReason(e) + ")");
  } catch (const nlohmann::json::exception& e) {  // a number too large for a double (out_of_range 406)
    detail::fail(source, "not JSON (" + jsonErrorText(e) + ")");
  }
  if (shape == JsonShape::Object && !j.is_object())
    detail::fail(source, "expected a JSON object, found " + withArticle(j));
  if (shape == JsonShape::Array && !j.is_array()) detail::fail(source, "expected a JSON array, found " + withArticle(j));
  return j;
}

nlohmann::json readJsonFile(const std::string& path, JsonShape shape) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) detail::fail(path, "cannot read (a folder, not a JSON file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::fail(path, std::string("cannot read (") + std::strerror(errno) + ")");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) detail::fail(path, "cannot read (a read failed part way)");
  return parseJson(text, path, shape);
}

}  // namespace keyturn
