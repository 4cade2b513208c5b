#pragma once
// The URIs the simulated OpenNI2 driver answers to:
//   keyturn-sim://default              the configuration $KEYTURN_OPENNI2_SIM_CONFIG names (or defaults)
//   keyturn-sim:///abs/path/sim.json   that configuration file (keyturn passes its own this way)
#include <optional>
#include <string>

namespace keyturn::sim::openni2 {

inline constexpr const char* kScheme = "keyturn-sim://";
inline constexpr const char* kDefaultUri = "keyturn-sim://default";
inline constexpr const char* kConfigVariable = "KEYTURN_OPENNI2_SIM_CONFIG";

// The configuration file a URI names: "" for the default device (read the
// environment), nullopt for a URI that is not this driver's.
inline std::optional<std::string> configPathOf(const std::string& uri) {
  const std::string scheme = kScheme;
  if (uri.compare(0, scheme.size(), scheme) != 0) return std::nullopt;
  const std::string rest = uri.substr(scheme.size());
  if (rest == "default") return std::string();
  if (!rest.empty() && rest[0] == '/') return rest;
  return std::nullopt;
}

}  // namespace keyturn::sim::openni2
