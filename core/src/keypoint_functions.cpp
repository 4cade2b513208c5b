#include "keyturn/core/keypoint_functions.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace keyturn {

std::vector<float> keypointDistances(const std::vector<Eigen::Vector3f>& kp) {
  const std::size_t k = kp.size();
  std::vector<float> out;
  out.reserve(k * (k - (k > 0)) / 2);
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) out.push_back((kp[a] - kp[b]).norm());
  return out;
}

std::vector<float> keypointSqrtAreas(const std::vector<Eigen::Vector3f>& kp) {
  const std::size_t k = kp.size();
  std::vector<float> out;
  if (k >= 3) out.reserve(k * (k - 1) * (k - 2) / 6);
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      const Eigen::Vector3f ab = kp[b] - kp[a];
      for (std::size_t c = b + 1; c < k; ++c)
        out.push_back(std::sqrt(0.5f * ab.cross(kp[c] - kp[a]).norm()));
    }
  return out;
}

namespace {
// The clamped cosine of the angle between two edge vectors of known squared lengths.
inline float cosineOf(const Eigen::Vector3f& u, const Eigen::Vector3f& v, float uu, float vv) {
  return std::clamp(u.dot(v) / std::sqrt(uu * vv), -1.0f, 1.0f);
}

// Calls visit(cosine, a, b, c) for each interior angle of every non-degenerate triangle (a, b, c),
// in the order keypointAngles lists them.
template <typename Visit>
void forEachAngleCosine(const std::vector<Eigen::Vector3f>& kp, Visit&& visit) {
  const std::size_t k = kp.size();
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      const Eigen::Vector3f ab = kp[b] - kp[a];
      const float lab = ab.squaredNorm();
      if (lab <= 0.f) continue;
      for (std::size_t c = b + 1; c < k; ++c) {
        const Eigen::Vector3f ac = kp[c] - kp[a], bc = kp[c] - kp[b];
        const float lac = ac.squaredNorm(), lbc = bc.squaredNorm();
        if (lac <= 0.f || lbc <= 0.f) continue;
        visit(cosineOf(ab, ac, lab, lac), a, b, c);     // at a
        visit(cosineOf(-ab, bc, lab, lbc), a, b, c);    // at b
        visit(cosineOf(-ac, -bc, lac, lbc), a, b, c);   // at c
      }
    }
}

// arccos within 6.7e-5 rad (Abramowitz & Stegun 4.4.45), for picking a bin before the exact call.
inline float roughArccos(float x) {
  const float ax = std::abs(x);
  const float r = std::sqrt(1.f - ax) * (1.5707288f + ax * (-0.2121144f + ax * (0.0742610f - 0.0187293f * ax)));
  return x >= 0.f ? r : static_cast<float>(M_PI) - r;
}
}  // namespace

std::vector<float> keypointAngles(const std::vector<Eigen::Vector3f>& kp) {
  const std::size_t k = kp.size();
  std::vector<float> out;
  if (k >= 3) out.reserve(k * (k - 1) * (k - 2) / 2);
  forEachAngleCosine(kp, [&](float c, std::size_t, std::size_t, std::size_t) { out.push_back(std::acos(c)); });
  return out;
}

std::vector<float> pairWeights(const std::vector<double>& w) {
  std::vector<float> out;
  for (std::size_t a = 0; a < w.size(); ++a)
    for (std::size_t b = a + 1; b < w.size(); ++b) out.push_back(static_cast<float>(w[a] * w[b]));
  return out;
}

std::vector<float> tripleWeights(const std::vector<double>& w) {
  std::vector<float> out;
  for (std::size_t a = 0; a < w.size(); ++a)
    for (std::size_t b = a + 1; b < w.size(); ++b)
      for (std::size_t c = b + 1; c < w.size(); ++c) out.push_back(static_cast<float>(w[a] * w[b] * w[c]));
  return out;
}

std::vector<double> keypointAnglePdf(const std::vector<Eigen::Vector3f>& kp, int bins, HistogramRange range,
                                     Binning binning, const std::vector<double>* weights) {
  bins = std::max(bins, 1);
  const double width = range.hi - range.lo;
  if (!(width > 0) && !weights) return histogramPdf(keypointAngles(kp), bins, range, nullptr, binning);
  if (binning != Binning::Hard || weights) {
    std::vector<double> pdf(bins, 0.0);
    double counted = 0;
    forEachAngleCosine(kp, [&](float c, std::size_t a, std::size_t b, std::size_t d) {
      if (!std::isfinite(c)) return;
      const double w = weights ? (*weights)[a] * (*weights)[b] * (*weights)[d] : 1.0;
      counted += w;
      addToHistogram(pdf, roughArccos(c), range, binning, w);
    });
    if (counted > 0)
      for (double& p : pdf) p /= counted;
    return pdf;
  }
  std::vector<std::size_t> count(bins, 0);
  std::size_t counted = 0;
  // The rough arccos decides the bin when it lies, in units of bins, farther than its error bound
  // (1e-4 rad, with room for float rounding) from both edges of the bin; otherwise the float
  // arccos keypointAngles uses, in histogramPdf's own bin (histogramBin).
  const float lo = static_cast<float>(range.lo), scale = static_cast<float>(bins / width);
  const float margin = static_cast<float>(1e-4 * bins / width);
  forEachAngleCosine(kp, [&](float c, std::size_t, std::size_t, std::size_t) {
    if (!std::isfinite(c)) return;
    ++counted;
    const float t = (roughArccos(c) - lo) * scale;
    if (t > margin && t < static_cast<float>(bins) - margin) {
      const int b = static_cast<int>(t);
      const float f = t - static_cast<float>(b);
      if (f > margin && f < 1.f - margin) {
        ++count[b];
        return;
      }
    }
    ++count[histogramBin(std::acos(c), bins, range)];
  });
  std::vector<double> pdf(bins, 0.0);
  if (counted > 0)
    for (int b = 0; b < bins; ++b) pdf[b] = static_cast<double>(count[b]) / static_cast<double>(counted);
  return pdf;
}

}  // namespace keyturn
