#pragma once
// Numbers as evaluate's fusion and next-best-view reports print them: one printf format per number,
// a percentage with "–" where there is none, and JSON null for a number that is not finite; and the
// flat single-view line both draw under their accuracy-against-views curves.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "keyturn/core/report_plot_specs.h"

namespace keyturn::learning::detail {

// `format` holds one %f, %g or %e conversion.
inline std::string formatNumber(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

inline nlohmann::json jsonNumber(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

inline std::string percent(double v) { return std::isfinite(v) ? formatNumber("%.1f", 100 * v) : "–"; }

// Single-view accuracy (0–1) as a flat line over views 1 … max_views (x counts from 0), in percent.
inline CurveSeries singleViewSeries(int max_views, double accuracy) {
  return CurveSeries{"single view", {0.0, static_cast<double>(max_views - 1)}, {100 * accuracy, 100 * accuracy}};
}

}  // namespace keyturn::learning::detail
