#include "keyturn/core/lens_distortion.h"

#include <cmath>

namespace keyturn {

Eigen::Vector2d LensDistortion::distort(const Eigen::Vector2d& p) const {
  const double x = p.x(), y = p.y(), r2 = x * x + y * y;
  const double radial = (1 + ((k3 * r2 + k2) * r2 + k1) * r2) / (1 + ((k6 * r2 + k5) * r2 + k4) * r2);
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x), y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

Eigen::Vector2d LensDistortion::undistort(const Eigen::Vector2d& d) const {
  if (none()) return d;
  // Fixed point of x = (x_d − tangential(x)) / radial(x), started at the distorted point.
  Eigen::Vector2d p = d;
  for (int i = 0; i < 50; ++i) {
    const double x = p.x(), y = p.y(), r2 = x * x + y * y;
    const double inverse_radial = (1 + ((k6 * r2 + k5) * r2 + k4) * r2) / (1 + ((k3 * r2 + k2) * r2 + k1) * r2);
    const Eigen::Vector2d next((d.x() - (2 * p1 * x * y + p2 * (r2 + 2 * x * x))) * inverse_radial,
                               (d.y() - (p1 * (r2 + 2 * y * y) + 2 * p2 * x * y)) * inverse_radial);
    const bool settled = (next - p).norm() < 1e-12;
    p = next;
    if (settled || !p.allFinite()) break;
  }
  return p;
}

}  // namespace keyturn
