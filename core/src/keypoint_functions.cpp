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
// Angle between two edge vectors of known squared lengths, via the clamped cosine.
inline float angleOf(const Eigen::Vector3f& u, const Eigen::Vector3f& v, float uu, float vv) {
  const float c = u.dot(v) / std::sqrt(uu * vv);
  return std::acos(std::clamp(c, -1.0f, 1.0f));
}
}  // namespace

std::vector<float> keypointAngles(const std::vector<Eigen::Vector3f>& kp) {
  const std::size_t k = kp.size();
  std::vector<float> out;
  if (k >= 3) out.reserve(k * (k - 1) * (k - 2) / 2);
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a + 1; b < k; ++b) {
      const Eigen::Vector3f ab = kp[b] - kp[a];
      const float lab = ab.squaredNorm();
      if (lab <= 0.f) continue;
      for (std::size_t c = b + 1; c < k; ++c) {
        const Eigen::Vector3f ac = kp[c] - kp[a], bc = kp[c] - kp[b];
        const float lac = ac.squaredNorm(), lbc = bc.squaredNorm();
        if (lac <= 0.f || lbc <= 0.f) continue;
        out.push_back(angleOf(ab, ac, lab, lac));     // at a
        out.push_back(angleOf(-ab, bc, lab, lbc));    // at b
        out.push_back(angleOf(-ac, -bc, lac, lbc));   // at c
      }
    }
  return out;
}

}  // namespace keyturn
