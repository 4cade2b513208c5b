#pragma once
// Numbers as evaluate's fusion and next-best-view reports print them: one printf format per number,
// a percentage with "–" where there is none, and JSON null for a number that is not finite.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

namespace keyturn::learning::detail {

// `format` holds one %f, %g or %e conversion.
inline std::string formatNumber(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

inline nlohmann::json jsonNumber(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

inline std::string percent(double v) { return std::isfinite(v) ? formatNumber("%.1f", 100 * v) : "–"; }

}  // namespace keyturn::learning::detail
