#include "keyturn/core/view_size.h"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace keyturn {

ViewSize viewSize(const std::vector<Eigen::Vector3f>& points) {
  ViewSize s;
  if (points.empty()) return s;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p.cast<double>();
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d d = p.cast<double>() - mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(points.size());
  s.rms_radius = std::sqrt(cov.trace());
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov, Eigen::EigenvaluesOnly).eigenvalues();
  for (int k = 0; k < 3; ++k) s.spread[k] = std::sqrt(std::max(0.0, ev[2 - k]));  // ascending → largest first
  return s;
}

}  // namespace keyturn
