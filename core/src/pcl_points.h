#pragma once
// keyturn's points as PCL's cloud: the one conversion, for every call into PCL (the k-d trees of
// keypoint_detectors, radius_search and repeatability, the filter's RANSAC, and the plugin
// "pcl_features", which compiles pcl_points.cpp into itself: a plugin links no keyturn library).
// Internal to keyturn_core; free of PCL's headers: PCL's types are only declared here.
#include <Eigen/Core>

#include <memory>
#include <vector>

namespace pcl {
struct PointXYZ;
template <typename PointT>
class PointCloud;
}  // namespace pcl

namespace keyturn {
struct Cloud;
}

namespace keyturn::detail {

using PclCloud = pcl::PointCloud<pcl::PointXYZ>;

// Every point, in order (NaNs too: the callers pass measured points).
std::shared_ptr<PclCloud> toPcl(const std::vector<Eigen::Vector3f>& points);
// The valid points of an organised cloud, in order; `index` (when given) gets the cloud index of each.
std::shared_ptr<PclCloud> toPcl(const Cloud& cloud, std::vector<int>* index = nullptr);

}  // namespace keyturn::detail
