#include "keyturn/bench/speed_ratio.h"

#include <cmath>
#include <cstdio>

namespace keyturn::bench {

std::string speedComparison(double ours_ms, double theirs_ms) {
  if (!(ours_ms > 0) || !(theirs_ms > 0) || !std::isfinite(ours_ms) || !std::isfinite(theirs_ms))
    return "not comparable (a time is missing)";
  const double ratio = theirs_ms / ours_ms;
  if (std::abs(ratio - 1.0) < 0.05) return "about as fast";
  char buf[64];
  if (ratio > 1.0)
    std::snprintf(buf, sizeof buf, "%.1f× faster", ratio);
  else
    std::snprintf(buf, sizeof buf, "%.1f× slower", 1.0 / ratio);
  return buf;
}

}  // namespace keyturn::bench
