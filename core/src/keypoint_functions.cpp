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
// The clamped cosine of the angle between two edge vectors, from their dot product and squared
// lengths: the one formula every angle below is computed by.
inline float clampedCosine(float dot, float uu, float vv) {
  const float c = dot / std::sqrt(uu * vv);
  return c < -1.0f ? -1.0f : 1.0f < c ? 1.0f : c;
}

// arccos within 6.7e-5 rad (Abramowitz & Stegun 4.4.45), for picking a bin before the exact call.
inline float roughArccos(float x) {
  const float ax = std::abs(x);
  const float r = std::sqrt(1.f - ax) * (1.5707288f + ax * (-0.2121144f + ax * (0.0742610f - 0.0187293f * ax)));
  return x >= 0.f ? r : static_cast<float>(M_PI) - r;
}

// The three interior angles' cosines of the triangles (a, b, c) for every c after b, in
// structure-of-arrays rows so that the compiler vectorises the loop over c (a scalar loop over
// Eigen's Vector3f was most of KPA3's time). Each lane does the float operations of the scalar
// formula in the same order (no contraction on the build's SSE2 baseline), so the cosines are
// bit-identical to it (tested against keypointAngles' recorded values).
class TriangleCosines {
 public:
  explicit TriangleCosines(const std::vector<Eigen::Vector3f>& kp) : k_(kp.size()) {
    x_.resize(k_), y_.resize(k_), z_.resize(k_);
    for (std::size_t i = 0; i < k_; ++i) x_[i] = kp[i].x(), y_[i] = kp[i].y(), z_[i] = kp[i].z();
    at_a.resize(k_), at_b.resize(k_), at_c.resize(k_), valid.resize(k_);
    rough_a.resize(k_), rough_b.resize(k_), rough_c.resize(k_);
  }
  std::size_t size() const { return k_; }

  // Fills at_a/at_b/at_c/valid[c] for c in (b, k), and with Rough their roughArccos in
  // rough_a/rough_b/rough_c; returns false when a and b coincide.
  template <bool Rough>
  bool row(std::size_t a, std::size_t b) {
    const float abx = x_[b] - x_[a], aby = y_[b] - y_[a], abz = z_[b] - z_[a];
    // Sums grouped as Eigen's fixed-size dot and squaredNorm group them: x + (y + z).
    const float lab = abx * abx + (aby * aby + abz * abz);
    if (lab <= 0.f) return false;
    const float *x = x_.data(), *y = y_.data(), *z = z_.data();
    const float ax = x[a], ay = y[a], az = z[a], bx = x[b], by = y[b], bz = z[b];
    float *ca = at_a.data(), *cb = at_b.data(), *cc = at_c.data();
    unsigned char* ok = valid.data();
    for (std::size_t c = b + 1; c < k_; ++c) {
      const float acx = x[c] - ax, acy = y[c] - ay, acz = z[c] - az;
      const float bcx = x[c] - bx, bcy = y[c] - by, bcz = z[c] - bz;
      const float lac = acx * acx + (acy * acy + acz * acz), lbc = bcx * bcx + (bcy * bcy + bcz * bcz);
      ok[c] = lac > 0.f && lbc > 0.f;
      ca[c] = clampedCosine(abx * acx + (aby * acy + abz * acz), lab, lac);        // at a: ab · ac
      cb[c] = clampedCosine(-abx * bcx + (-aby * bcy + -abz * bcz), lab, lbc);     // at b: −ab · bc
      cc[c] = clampedCosine(-acx * -bcx + (-acy * -bcy + -acz * -bcz), lac, lbc);  // at c: −ac · −bc
    }
    if (Rough) {
      float *ra = rough_a.data(), *rb = rough_b.data(), *rc = rough_c.data();
      for (std::size_t c = b + 1; c < k_; ++c) ra[c] = roughArccos(ca[c]), rb[c] = roughArccos(cb[c]), rc[c] = roughArccos(cc[c]);
    }
    return true;
  }

  std::vector<float> at_a, at_b, at_c, rough_a, rough_b, rough_c;
  std::vector<unsigned char> valid;

 private:
  std::size_t k_;
  std::vector<float> x_, y_, z_;
};

// Calls visit(cosine, rough arccos, a, b, c) for each interior angle of every non-degenerate
// triangle (a, b, c), in the order keypointAngles lists them (the rough arccos only with Rough).
template <bool Rough, typename Visit>
void forEachAngleCosine(const std::vector<Eigen::Vector3f>& kp, Visit&& visit) {
  TriangleCosines t(kp);
  const std::size_t k = t.size();
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      if (!t.template row<Rough>(a, b)) continue;
      for (std::size_t c = b + 1; c < k; ++c) {
        if (!t.valid[c]) continue;
        visit(t.at_a[c], t.rough_a[c], a, b, c);
        visit(t.at_b[c], t.rough_b[c], a, b, c);
        visit(t.at_c[c], t.rough_c[c], a, b, c);
      }
    }
}

}  // namespace

std::vector<float> keypointAngles(const std::vector<Eigen::Vector3f>& kp) {
  const std::size_t k = kp.size();
  std::vector<float> out;
  if (k >= 3) out.reserve(k * (k - 1) * (k - 2) / 2);
  forEachAngleCosine<false>(kp, [&](float c, float, std::size_t, std::size_t, std::size_t) { out.push_back(std::acos(c)); });
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
  if (binning == Binning::Linear && !weights && bins >= 2) {
    std::vector<double> pdf(bins, 0.0);
    std::size_t counted = 0;
    forEachAngleCosine<true>(kp, [&](float c, float rough, std::size_t, std::size_t, std::size_t) {
      if (!std::isfinite(c)) return;
      ++counted;
      addLinearToHistogram(pdf.data(), bins, rough, range);
    });
    if (counted > 0)
      for (double& p : pdf) p /= static_cast<double>(counted);
    return pdf;
  }
  if (binning != Binning::Hard || weights) {
    std::vector<double> pdf(bins, 0.0);
    double counted = 0;
    forEachAngleCosine<true>(kp, [&](float c, float rough, std::size_t a, std::size_t b, std::size_t d) {
      if (!std::isfinite(c)) return;
      const double w = weights ? (*weights)[a] * (*weights)[b] * (*weights)[d] : 1.0;
      counted += w;
      addToHistogram(pdf, rough, range, binning, w);
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
  forEachAngleCosine<true>(kp, [&](float c, float rough, std::size_t, std::size_t, std::size_t) {
    if (!std::isfinite(c)) return;
    ++counted;
    const float t = (rough - lo) * scale;
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
