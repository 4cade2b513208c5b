#pragma once
// A lens's radial and tangential distortion as ROS and OpenCV write it: plumb_bob (k1, k2, p1, p2,
// k3; also called radial-tangential or Brown–Conrady) and rational_polynomial (k4, k5, k6 below the
// fraction). Both act on normalised image coordinates (x, y) = ((u − cx) / fx, (v − cy) / fy):
//
//   r² = x² + y²,  radial = (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶)
//   x_d = x · radial + 2 p1 x y + p2 (r² + 2 x²),   y_d = y · radial + p1 (r² + 2 y²) + 2 p2 x y
//
// A depth camera's pixel (u, v) sees the ray through the *undistorted* (x, y) whose distortion lands
// on it, which has no closed form: undistort() finds it by fixed-point iteration, as OpenCV's
// undistortPoints does.
#include <Eigen/Core>

namespace keyturn {

struct LensDistortion {
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0, k4 = 0, k5 = 0, k6 = 0;

  bool none() const { return k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && k3 == 0 && k4 == 0 && k5 == 0 && k6 == 0; }
  // Where the lens puts the ray through normalised coordinates (x, y).
  Eigen::Vector2d distort(const Eigen::Vector2d& undistorted) const;
  // The ray whose distortion lands on `distorted` (normalised coordinates): iterated until it moves
  // less than 1e-12 (at most 50 times; strong distortion far outside the calibrated field may not
  // converge, and then the last estimate is returned).
  Eigen::Vector2d undistort(const Eigen::Vector2d& distorted) const;
};

}  // namespace keyturn
