#pragma once
// Integer settings from JSON files (device profiles, simulator configurations,
// model sidecars), for the libraries that link nlohmann_json. JSON has one number
// type: nlohmann's get<int>() casts 1e30 (undefined behaviour) and wraps
// 4294967297 to 1, so every integer is read as a double and range-checked.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "keyturn/core/checked_integer.h"
#include "keyturn/core/error.h"

namespace keyturn {

// j[key] as a T in [lo, hi]; Error "<where>: <key> must be an integer in lo..hi, not <value>".
template <typename T>
T jsonInteger(const nlohmann::json& j, const std::string& key, T lo, T hi, const std::string& where) {
  const nlohmann::json& v = j.at(key);
  std::optional<T> t;
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();  // exact, even past 2^53
    if (hi >= 0 && u <= static_cast<std::uint64_t>(hi) && (lo <= 0 || u >= static_cast<std::uint64_t>(lo))) t = static_cast<T>(u);
  } else if (v.is_number()) {
    t = integerIn(v.get<double>(), lo, hi);
  }
  if (!t)
    throw Error(where + ": " + key + " must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                ", not " + v.dump().substr(0, 40));
  return *t;
}

// The same with a default when the key is absent.
template <typename T>
T jsonInteger(const nlohmann::json& j, const std::string& key, T fallback, T lo, T hi, const std::string& where) {
  return j.contains(key) ? jsonInteger(j, key, lo, hi, where) : fallback;
}

}  // namespace keyturn
