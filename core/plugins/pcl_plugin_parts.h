#pragma once
// The functions of the plugin "pcl_features", one per entry of detail::PclFeatures.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include "../src/pcl_features_plugin.h"
#include "../src/pcl_points.h"

namespace keyturn::pcl_plugin {

using detail::toPcl;  // ../src/pcl_points.cpp, compiled into the plugin too
// Normals (and curvature) from a radius search of `radius` metres over `tree`.
pcl::PointCloud<pcl::Normal>::Ptr normalsOf(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud,
                                            const pcl::search::KdTree<pcl::PointXYZ>::Ptr& tree, double radius);

std::vector<Eigen::Vector3f> issKeypoints(const PointSet& set, double frame_radius, double nms_radius,
                                          double gamma21, double gamma32, int min_neighbors);
std::vector<float> esf(const PointSet& set);
std::vector<float> esfSeeded(const PointSet& set, unsigned seed);
std::vector<float> ourCvfh(const PointSet& set, double normal_radius);
std::vector<float> vfh(const PointSet& set, double normal_radius);
std::vector<detail::PointValue> harris(const PointSet& set, double radius, bool non_max_suppression);
std::vector<float> curvature(const PointSet& set, double normal_radius);
std::vector<Eigen::Vector3f> sift(const PointSet& set, double normal_radius, float min_scale, int octaves,
                                  int scales_per_octave, float min_contrast);
IcpRefinement icp(const std::vector<Eigen::Vector3f>& model, const std::vector<Eigen::Vector3f>& scene,
                  const Eigen::Matrix4d& initial, double max_distance, int iterations);

}  // namespace keyturn::pcl_plugin
