// The plugin "pcl_features": PCL's Harris3D and SIFT3D detectors and its ICP, whose templates are
// not precompiled in Debian's PCL, so this is the one translation unit that instantiates them.
#include <pcl/features/normal_3d.h>
#include <pcl/keypoints/harris_3d.h>
#include <pcl/keypoints/sift_keypoint.h>
#include <pcl/registration/icp.h>
#include <pcl/search/kdtree.h>

#include <cmath>

#include "pcl_plugin_parts.h"

namespace keyturn::pcl_plugin {

std::vector<detail::PointValue> harris(const PointSet& set, double radius, bool non_max_suppression) {
  auto cloud = toPcl(set.points);
  pcl::HarrisKeypoint3D<pcl::PointXYZ, pcl::PointXYZI> h(pcl::HarrisKeypoint3D<pcl::PointXYZ, pcl::PointXYZI>::HARRIS);
  h.setInputCloud(cloud);
  h.setRadius(radius);
  h.setNonMaxSupression(non_max_suppression);
  h.setRefine(false);
  h.setNumberOfThreads(1);
  pcl::PointCloud<pcl::PointXYZI> kp;
  h.compute(kp);
  std::vector<detail::PointValue> out;
  out.reserve(kp.size());
  for (const auto& p : kp) out.push_back({Eigen::Vector3f(p.x, p.y, p.z), p.intensity});
  return out;
}

std::vector<float> curvature(const PointSet& set, double normal_radius) {
  const auto n = normalsOf(toPcl(set.points), pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>),
                           normal_radius);
  std::vector<float> out(n->size());
  for (std::size_t i = 0; i < n->size(); ++i) out[i] = (*n)[i].curvature;
  return out;
}

std::vector<Eigen::Vector3f> sift(const PointSet& set, double normal_radius, float min_scale, int octaves,
                                  int scales_per_octave, float min_contrast) {
  // SIFT on the surface curvature (PCL's PointNormal field selector picks it).
  auto cloud = toPcl(set.points);
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::NormalEstimation<pcl::PointXYZ, pcl::PointNormal> ne;
  ne.setInputCloud(cloud);
  ne.setSearchMethod(tree);
  ne.setRadiusSearch(normal_radius);
  pcl::PointCloud<pcl::PointNormal>::Ptr pn(new pcl::PointCloud<pcl::PointNormal>);
  ne.compute(*pn);
  for (std::size_t i = 0; i < pn->size(); ++i) {
    (*pn)[i].x = (*cloud)[i].x;
    (*pn)[i].y = (*cloud)[i].y;
    (*pn)[i].z = (*cloud)[i].z;
  }
  pcl::SIFTKeypoint<pcl::PointNormal, pcl::PointWithScale> detector;
  pcl::search::KdTree<pcl::PointNormal>::Ptr tree2(new pcl::search::KdTree<pcl::PointNormal>);
  detector.setSearchMethod(tree2);
  detector.setScales(min_scale, octaves, scales_per_octave);
  detector.setMinimumContrast(min_contrast);
  detector.setInputCloud(pn);
  pcl::PointCloud<pcl::PointWithScale> kp;
  detector.compute(kp);
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : kp) out.emplace_back(p.x, p.y, p.z);
  return out;
}

IcpRefinement icp(const std::vector<Eigen::Vector3f>& model, const std::vector<Eigen::Vector3f>& scene,
                  const Eigen::Matrix4d& initial, double max_distance, int iterations) {
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> registration;
  registration.setInputSource(toPcl(model));
  registration.setInputTarget(toPcl(scene));
  registration.setMaxCorrespondenceDistance(max_distance);
  registration.setMaximumIterations(iterations);
  registration.setTransformationEpsilon(1e-10);
  registration.setEuclideanFitnessEpsilon(1e-12);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  registration.align(aligned, initial.cast<float>());
  IcpRefinement r;
  r.converged = registration.hasConverged();
  r.scene_from_model = registration.getFinalTransformation().cast<double>();
  r.rms_m = std::sqrt(registration.getFitnessScore(max_distance));
  return r;
}

}  // namespace keyturn::pcl_plugin
