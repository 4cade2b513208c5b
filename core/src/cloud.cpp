#include "keyturn/core/cloud.h"

namespace keyturn {

std::size_t Cloud::validCount() const {
  std::size_t n = 0;
  for (const auto& p : points) n += isValid(p) ? 1 : 0;
  return n;
}

PointSet PointSet::fromCloud(const Cloud& cloud) {
  PointSet set;
  set.points.reserve(cloud.points.size());
  const bool organized = cloud.organized();
  if (organized) {
    set.width = cloud.width;
    set.height = cloud.height;
    set.pixel_to_point.assign(cloud.points.size(), -1);
  }
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (!Cloud::isValid(cloud.points[i])) continue;
    if (organized) {
      set.pixel_to_point[i] = static_cast<int>(set.points.size());
      set.pixel.push_back(static_cast<int>(i));
    }
    set.points.push_back(cloud.points[i]);
  }
  return set;
}

Eigen::Vector3f PointSet::centroid() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : points) sum += p.cast<double>();
  if (points.empty()) return Eigen::Vector3f::Zero();
  return (sum / static_cast<double>(points.size())).cast<float>();
}

}  // namespace keyturn
