#include "keyturn/core/json_error.h"

#include "keyturn/core/string_format.h"

namespace keyturn {

std::string jsonErrorText(const nlohmann::json::exception& e) {
  std::string s = printableText(e.what());  // a parse error quotes the file's bytes
  if (s.rfind("[json.exception.", 0) == 0) {
    const auto end = s.find("] ");
    if (end != std::string::npos) s.erase(0, end + 2);
  }
  if (e.id == 403) {  // out_of_range.403: "key 'KEY' not found"
    const auto a = s.find('\''), b = s.rfind('\'');
    if (a != std::string::npos && b > a) return s.substr(a, b - a + 1) + " is missing";
  }
  constexpr std::size_t kMost = 160;  // a parse error quotes what it last read, which may be long
  if (s.size() > kMost) {
    const auto space = s.rfind(' ', kMost);
    s = s.substr(0, space == std::string::npos ? kMost : space) + " …";
  }
  return s;
}

}  // namespace keyturn
