#pragma once
// How big a view is: the scale its scale-normalised PDFs divide lengths by, and the
// small explicit size block a classifier can use beside them (docs/descriptors.md).
#include <vector>

#include <Eigen/Core>

namespace keyturn {

// The normalised ranges' extent in RMS radii: a thin rod of length L has an RMS radius of
// L/√12, so its longest distance is √12 ≈ 3.46 radii; rounder views stay well inside.
constexpr double kScaledExtent = 3.5;

struct ViewSize {
  double rms_radius = 0;           // RMS distance of the points from their centroid (m)
  Eigen::Vector3d spread{0, 0, 0};  // square roots of the covariance's eigenvalues, largest first (m)
  std::vector<double> block() const { return {rms_radius, spread.x(), spread.y(), spread.z()}; }
};
constexpr int kSizeBlockWidth = 4;

// The RMS radius is of all the view's points, not of its keypoints, so the scale does not move
// with the keypoints it normalises; at the working resolution the points are spread evenly over
// the surface, so it measures the surface seen, not the sensor's sampling density.
ViewSize viewSize(const std::vector<Eigen::Vector3f>& points);

}  // namespace keyturn
