#include "keyturn/core/pcl_baselines.h"

#include <pcl/features/esf.h>
#include <pcl/features/normal_3d.h>
#include <pcl/features/vfh.h>
#include <pcl/keypoints/iss_3d.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

namespace keyturn {
namespace {
pcl::PointCloud<pcl::PointXYZ>::Ptr toPcl(const PointSet& set) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr c(new pcl::PointCloud<pcl::PointXYZ>);
  c->reserve(set.size());
  for (const auto& p : set.points) c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return c;
}
}  // namespace

std::vector<Eigen::Vector3f> pclIssKeypoints(const PointSet& set, double frame_radius,
                                             double nms_radius, double gamma21, double gamma32,
                                             int min_neighbors) {
  auto cloud = toPcl(set);
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

std::vector<float> pclEsf(const PointSet& set) {
  auto cloud = toPcl(set);
  pcl::ESFEstimation<pcl::PointXYZ, pcl::ESFSignature640> esf;
  esf.setInputCloud(cloud);
  pcl::PointCloud<pcl::ESFSignature640> out;
  esf.compute(out);
  if (out.empty()) return {};
  return std::vector<float>(out[0].histogram, out[0].histogram + 640);
}

std::vector<float> pclVfh(const PointSet& set, double normal_radius) {
  auto cloud = toPcl(set);
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  ne.setInputCloud(cloud);
  ne.setSearchMethod(tree);
  ne.setRadiusSearch(normal_radius);
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  ne.compute(*normals);
  pcl::VFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> vfh;
  vfh.setInputCloud(cloud);
  vfh.setInputNormals(normals);
  vfh.setSearchMethod(tree);
  pcl::PointCloud<pcl::VFHSignature308> out;
  vfh.compute(out);
  if (out.empty()) return {};
  return std::vector<float>(out[0].histogram, out[0].histogram + 308);
}

}  // namespace keyturn
