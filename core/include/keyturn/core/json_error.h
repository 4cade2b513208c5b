#pragma once
// What is wrong with a JSON file, from the JSON library's exception, in keyturn's words: for the
// readers of JSON files (model sidecars, evaluation parts, camera files, sidecars, profiles), whose
// errors name the file and then this.
#include <nlohmann/json.hpp>
#include <string>

namespace keyturn {

// e.what() without nlohmann's "[json.exception.KIND.ID] " prefix, a missing key as "'KEY' is
// missing", and at most about 160 characters, cut between words ("…"), never inside one.
std::string jsonErrorText(const nlohmann::json::exception& e);

}  // namespace keyturn
