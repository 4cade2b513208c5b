#include "keyturn/core/histogram.h"

#include <algorithm>
#include <cmath>

namespace keyturn {

std::vector<double> histogramPdf(const std::vector<float>& values, int bins, HistogramRange range,
                                 int* clamped) {
  std::vector<double> pdf(std::max(bins, 1), 0.0);
  const double width = range.hi - range.lo;
  std::size_t counted = 0;
  int outside = 0;
  for (float v : values) {
    if (!std::isfinite(v)) continue;
    // The bin is found in double and bounded before it becomes an int: a far
    // outlier from a file (1e30 m) is far past INT_MAX bins.
    const double t = width > 0 ? std::floor((v - range.lo) / width * bins) : 0.0;
    int b = !(t >= 0) ? -1 : t > bins ? bins + 1 : static_cast<int>(t);
    if (b < 0 || b >= bins) {
      // The upper edge itself belongs to the last bin; anything beyond is clamped.
      if (!(b == bins && v <= range.hi)) ++outside;
      b = std::clamp(b, 0, bins - 1);
    }
    pdf[b] += 1.0;
    ++counted;
  }
  if (counted > 0)
    for (double& p : pdf) p /= static_cast<double>(counted);
  if (clamped) *clamped = outside;
  return pdf;
}

}  // namespace keyturn
