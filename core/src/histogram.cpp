#include "keyturn/core/histogram.h"

#include <algorithm>
#include <cmath>

namespace keyturn {

int histogramBin(double v, int bins, HistogramRange range) {
  bins = std::max(bins, 1);
  const double width = range.hi - range.lo;
  // The bin is found in double and bounded before it becomes an int: a far
  // outlier from a file (1e30 m) is far past INT_MAX bins.
  const double t = width > 0 ? std::floor((v - range.lo) / width * bins) : 0.0;
  return !(t >= 0) ? 0 : t >= bins ? bins - 1 : static_cast<int>(t);
}

std::vector<double> histogramPdf(const std::vector<float>& values, int bins, HistogramRange range,
                                 int* clamped) {
  std::vector<double> pdf(std::max(bins, 1), 0.0);
  std::size_t counted = 0;
  int outside = 0;
  for (float v : values) {
    if (!std::isfinite(v)) continue;
    // Outside [lo, hi] goes into the first/last bin and is counted as clamped (hi itself
    // belongs to the last bin).
    if (range.hi > range.lo && (v < range.lo || v > range.hi)) ++outside;
    pdf[histogramBin(v, bins, range)] += 1.0;
    ++counted;
  }
  if (counted > 0)
    for (double& p : pdf) p /= static_cast<double>(counted);
  if (clamped) *clamped = outside;
  return pdf;
}

}  // namespace keyturn
