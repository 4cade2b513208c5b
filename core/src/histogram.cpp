#include "keyturn/core/histogram.h"

#include <algorithm>
#include <cmath>

#include "keyturn/core/error.h"

namespace keyturn {

int histogramBin(double v, int bins, HistogramRange range) {
  bins = std::max(bins, 1);
  const double width = range.hi - range.lo;
  // The bin is found in double and bounded before it becomes an int: a far
  // outlier from a file (1e30 m) is far past INT_MAX bins.
  const double t = width > 0 ? std::floor((v - range.lo) / width * bins) : 0.0;
  return !(t >= 0) ? 0 : t >= bins ? bins - 1 : static_cast<int>(t);
}

const char* binningName(Binning b) {
  return b == Binning::Hard ? "hard" : b == Binning::Linear ? "linear" : "quadratic";
}

Binning parseBinning(const std::string& name) {
  if (name == "hard") return Binning::Hard;
  if (name == "linear") return Binning::Linear;
  if (name == "quadratic") return Binning::Quadratic;
  throw Error("must be hard, linear or quadratic, not '" + name + "'");
}

void addToHistogram(std::vector<double>& pdf, double v, HistogramRange range, Binning binning, double weight) {
  const int bins = static_cast<int>(pdf.size());
  const double width = range.hi - range.lo;
  if (binning == Binning::Hard || !(width > 0) || bins < 2) {
    pdf[histogramBin(v, bins, range)] += weight;
    return;
  }
  if (binning == Binning::Quadratic) {
    // Position in bin units from the first bin's centre; bounded in double before any int.
    const double t = (v - range.lo) / width * bins - 0.5;
    // The nearest centre c and the B-spline's weights on c − 1, c, c + 1 (they sum to 1).
    const double near = !(t > 0) ? 0.0 : !(t < bins - 1) ? bins - 1.0 : std::floor(t + 0.5);
    const double f = std::clamp(t - near, -0.5, 0.5);  // beyond an end centre: all as at the end
    const int c = static_cast<int>(near);
    const double left = 0.5 * (0.5 - f) * (0.5 - f), right = 0.5 * (0.5 + f) * (0.5 + f);
    pdf[c] += weight * (0.75 - f * f);
    pdf[c > 0 ? c - 1 : c] += weight * left;
    pdf[c + 1 < bins ? c + 1 : c] += weight * right;
    return;
  }
  addLinearToHistogram(pdf.data(), bins, v, range, weight);
}

std::vector<double> histogramPdf(const std::vector<float>& values, int bins, HistogramRange range,
                                 int* clamped, Binning binning, const std::vector<float>* weights) {
  std::vector<double> pdf(std::max(bins, 1), 0.0);
  double counted = 0;
  int outside = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float v = values[i];
    if (!std::isfinite(v)) continue;
    // Outside [lo, hi] goes into the first/last bin and is counted as clamped (hi itself
    // belongs to the last bin).
    if (range.hi > range.lo && (v < range.lo || v > range.hi)) ++outside;
    const double w = weights ? (*weights)[i] : 1.0;
    addToHistogram(pdf, v, range, binning, w);
    counted += w;
  }
  if (counted > 0)
    for (double& p : pdf) p /= counted;
  if (clamped) *clamped = outside;
  return pdf;
}

void smoothPdf(std::vector<double>& pdf, double sigma_bins) {
  const int n = static_cast<int>(pdf.size());
  if (!(sigma_bins > 0) || n < 2) return;
  const int reach = static_cast<int>(std::ceil(3.0 * sigma_bins));
  std::vector<double> kernel(2 * reach + 1);
  double kernel_sum = 0;
  for (int d = -reach; d <= reach; ++d)
    kernel_sum += kernel[d + reach] = std::exp(-0.5 * (d / sigma_bins) * (d / sigma_bins));
  for (double& k : kernel) k /= kernel_sum;  // once, not per bin and tap
  std::vector<double> out(pdf.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    if (pdf[i] == 0) continue;
    for (int d = -reach; d <= reach; ++d) {
      int j = i + d;
      while (j < 0 || j >= n) j = j < 0 ? -1 - j : 2 * n - 1 - j;  // reflected at the outer bin edges
      out[j] += pdf[i] * kernel[d + reach];
    }
  }
  pdf.swap(out);
}

}  // namespace keyturn
