#include "keyturn/core/shape_distributions.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace keyturn {

std::vector<float> osadaShapeFunction(const std::vector<Eigen::Vector3f>& pts, OsadaFunction f,
                                      const OsadaOptions& options) {
  std::vector<float> out;
  const std::size_t n = pts.size();
  const std::size_t need = f == OsadaFunction::D1 ? 1 : f == OsadaFunction::D2 ? 2
                           : f == OsadaFunction::D4 ? 4 : 3;
  if (n < need || options.samples <= 0) return out;
  std::mt19937_64 rng(options.seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  out.reserve(options.samples);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  if (f == OsadaFunction::D1) {
    for (const auto& p : pts) c += p.cast<double>();
    c /= static_cast<double>(n);
  }
  const Eigen::Vector3f cf = c.cast<float>();
  for (int s = 0; s < options.samples; ++s) {
    const Eigen::Vector3f& a = pts[pick(rng)];
    switch (f) {
      case OsadaFunction::D1: out.push_back((a - cf).norm()); break;
      case OsadaFunction::D2: out.push_back((a - pts[pick(rng)]).norm()); break;
      case OsadaFunction::D3: {
        const Eigen::Vector3f& b = pts[pick(rng)];
        const Eigen::Vector3f& d = pts[pick(rng)];
        out.push_back(std::sqrt(0.5f * (b - a).cross(d - a).norm()));
        break;
      }
      case OsadaFunction::D4: {
        const Eigen::Vector3f& b = pts[pick(rng)];
        const Eigen::Vector3f& d = pts[pick(rng)];
        const Eigen::Vector3f& e = pts[pick(rng)];
        const float vol = std::abs((b - a).dot((d - a).cross(e - a))) / 6.0f;
        out.push_back(std::cbrt(vol));
        break;
      }
      case OsadaFunction::A3: {
        const Eigen::Vector3f& m = pts[pick(rng)];  // the vertex of the angle
        const Eigen::Vector3f& b = pts[pick(rng)];
        const Eigen::Vector3f u = a - m, v = b - m;
        const float uu = u.squaredNorm(), vv = v.squaredNorm();
        if (uu <= 0.f || vv <= 0.f) break;  // a repeated point has no angle
        out.push_back(std::acos(std::clamp(u.dot(v) / std::sqrt(uu * vv), -1.f, 1.f)));
        break;
      }
    }
  }
  return out;
}

}  // namespace keyturn
