// The plugin "pcl_features" (src/pcl_features_plugin.h): PCL's global descriptors, its ISS, and
// (pcl_detectors.cpp) its Harris3D, SIFT3D and ICP, on keyturn's point sets.
#include <cmath>

#include <pcl/features/esf.h>
#include <pcl/features/normal_3d.h>
#include <pcl/features/our_cvfh.h>
#include <pcl/features/vfh.h>
#include <pcl/keypoints/iss_3d.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include "../src/pcl_features_plugin.h"
#include "keyturn/core/plugin.h"
#include "pcl_plugin_parts.h"

namespace keyturn::pcl_plugin {

pcl::PointCloud<pcl::Normal>::Ptr normalsOf(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud,
                                            const pcl::search::KdTree<pcl::PointXYZ>::Ptr& tree, double radius) {
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  ne.setInputCloud(cloud);
  ne.setSearchMethod(tree);
  ne.setRadiusSearch(radius);
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  ne.compute(*normals);
  return normals;
}

std::vector<Eigen::Vector3f> issKeypoints(const PointSet& set, double frame_radius, double nms_radius,
                                          double gamma21, double gamma32, int min_neighbors) {
  auto cloud = toPcl(set.points);
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::ISSKeypoint3D<pcl::PointXYZ, pcl::PointXYZ> iss;
  iss.setSearchMethod(tree);
  iss.setSalientRadius(frame_radius);
  iss.setNonMaxRadius(nms_radius);
  iss.setThreshold21(gamma21);
  iss.setThreshold32(gamma32);
  iss.setMinNeighbors(min_neighbors);
  iss.setNumberOfThreads(1);
  iss.setInputCloud(cloud);
  pcl::PointCloud<pcl::PointXYZ> kp;
  iss.compute(kp);
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : kp) out.emplace_back(p.x, p.y, p.z);
  return out;
}

std::vector<float> esf(const PointSet& set) {
  auto cloud = toPcl(set.points);
  pcl::ESFEstimation<pcl::PointXYZ, pcl::ESFSignature640> esf;
  esf.setInputCloud(cloud);
  pcl::PointCloud<pcl::ESFSignature640> out;
  esf.compute(out);
  if (out.empty()) return {};
  return std::vector<float>(out[0].histogram, out[0].histogram + 640);
}

std::vector<float> vfh(const PointSet& set, double normal_radius) {
  auto cloud = toPcl(set.points);
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  auto normals = normalsOf(cloud, tree, normal_radius);
  pcl::VFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> vfh;
  vfh.setInputCloud(cloud);
  vfh.setInputNormals(normals);
  vfh.setSearchMethod(tree);
  pcl::PointCloud<pcl::VFHSignature308> out;
  vfh.compute(out);
  if (out.empty()) return {};
  return std::vector<float>(out[0].histogram, out[0].histogram + 308);
}

std::vector<float> ourCvfh(const PointSet& set, double normal_radius) {
  auto cloud = toPcl(set.points);
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  auto normals = normalsOf(cloud, tree, normal_radius);
  // Points with too few neighbours get NaN normals; PCL's OUR-CVFH then builds a
  // NaN reference frame and indexes its histogram out of bounds (an assertion in
  // Debian's build). Keep only points with a finite normal.
  pcl::PointCloud<pcl::PointXYZ>::Ptr kept(new pcl::PointCloud<pcl::PointXYZ>);
  pcl::PointCloud<pcl::Normal>::Ptr kept_normals(new pcl::PointCloud<pcl::Normal>);
  for (std::size_t i = 0; i < normals->size(); ++i) {
    const auto& n = (*normals)[i];
    if (!std::isfinite(n.normal_x) || !std::isfinite(n.normal_y) || !std::isfinite(n.normal_z) ||
        !std::isfinite(n.curvature))
      continue;
    kept->push_back((*cloud)[i]);
    kept_normals->push_back(n);
  }
  if (kept->size() < 50) return {};
  cloud = kept;
  normals = kept_normals;
  tree->setInputCloud(cloud);
  pcl::OURCVFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> cvfh;
  cvfh.setInputCloud(cloud);
  cvfh.setInputNormals(normals);
  cvfh.setSearchMethod(tree);
  // PCL's recommended region growing: 5° normal deviation, curvature ≤ 1, ≥ 50 points.
  cvfh.setEPSAngleThreshold(5.0f / 180.0f * static_cast<float>(M_PI));
  cvfh.setCurvatureThreshold(1.0f);
  cvfh.setNormalizeBins(false);
  cvfh.setClusterTolerance(static_cast<float>(3 * normal_radius));
  cvfh.setMinPoints(50);
  cvfh.setAxisRatio(0.8f);
  pcl::PointCloud<pcl::VFHSignature308> out;
  cvfh.compute(out);
  if (out.empty()) return {};
  return std::vector<float>(out[0].histogram, out[0].histogram + 308);
}

}  // namespace keyturn::pcl_plugin

KEYTURN_PLUGIN_EXPORT const keyturn::detail::PclFeatures* keyturn_pcl_features() {
  using namespace keyturn::pcl_plugin;
  static const keyturn::detail::PclFeatures table{issKeypoints, esf,      esfSeeded, ourCvfh, vfh,
                                                  harris,       curvature, sift,     icp};
  return &table;
}
