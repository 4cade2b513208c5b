#include "keyturn/core/repeatability.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>

#include "pcl_features_plugin.h"
#include "pcl_points.h"

namespace keyturn {
namespace {
using detail::toPcl;

double nearest(const pcl::KdTreeFLANN<pcl::PointXYZ>& tree, bool empty, const Eigen::Vector3f& q) {
  if (empty) return std::numeric_limits<double>::infinity();
  pcl::Indices idx(1);
  std::vector<float> d2(1);
  if (tree.nearestKSearch(pcl::PointXYZ(q.x(), q.y(), q.z()), 1, idx, d2) < 1)
    return std::numeric_limits<double>::infinity();
  return std::sqrt(d2[0]);
}
}  // namespace

RepeatabilityResult keypointRepeatability(const std::vector<Eigen::Vector3f>& model_kp,
                                          const std::vector<Eigen::Vector3f>& scene_kp, const PointSet& scene,
                                          double res, const Eigen::Matrix4d& T, const std::vector<double>& eps,
                                          double vis_res) {
  RepeatabilityResult r;
  r.model_keypoints = static_cast<int>(model_kp.size());
  r.scene_keypoints = static_cast<int>(scene_kp.size());
  r.absolute.assign(eps.size(), 0);
  r.relative.assign(eps.size(), 0.0);
  pcl::KdTreeFLANN<pcl::PointXYZ> points_tree, kp_tree;
  const auto scene_cloud = toPcl(scene.points), kp_cloud = toPcl(scene_kp);
  if (!scene_cloud->empty()) points_tree.setInputCloud(scene_cloud);
  if (!kp_cloud->empty()) kp_tree.setInputCloud(kp_cloud);
  const Eigen::Matrix3f R = T.topLeftCorner<3, 3>().cast<float>();
  const Eigen::Vector3f t = T.topRightCorner<3, 1>().cast<float>();
  for (const auto& m : model_kp) {
    const Eigen::Vector3f q = R * m + t;
    // Not on the scene's surface: occluded or outside its view, so it cannot repeat.
    if (nearest(points_tree, scene_cloud->empty(), q) > vis_res * res) continue;
    ++r.visible;
    const double d = nearest(kp_tree, kp_cloud->empty(), q);
    for (std::size_t e = 0; e < eps.size(); ++e)
      if (d <= eps[e]) ++r.absolute[e];
  }
  for (std::size_t e = 0; e < eps.size(); ++e)
    r.relative[e] = r.visible > 0 ? static_cast<double>(r.absolute[e]) / r.visible : 0.0;
  return r;
}

double overlapFraction(const PointSet& a, const PointSet& b, const Eigen::Matrix4d& b_from_a, double radius_m,
                       std::size_t max_points) {
  if (a.size() == 0 || b.size() == 0) return 0.0;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(toPcl(b.points));
  const Eigen::Matrix3f R = b_from_a.topLeftCorner<3, 3>().cast<float>();
  const Eigen::Vector3f t = b_from_a.topRightCorner<3, 1>().cast<float>();
  const std::size_t stride = std::max<std::size_t>(1, (a.size() + max_points - 1) / std::max<std::size_t>(max_points, 1));
  std::size_t near = 0, tried = 0;
  for (std::size_t i = 0; i < a.size(); i += stride, ++tried)
    if (nearest(tree, false, R * a.points[i] + t) <= radius_m) ++near;
  return static_cast<double>(near) / static_cast<double>(tried);
}

// PCL's ICP (libpcl_registration) is in the plugin "pcl_features".
IcpRefinement refineByIcp(const PointSet& model, const PointSet& scene, const Eigen::Matrix4d& initial,
                          double max_distance, int iterations) {
  return detail::pclFeatures().icp(model.points, scene.points, initial, max_distance, iterations);
}

}  // namespace keyturn
