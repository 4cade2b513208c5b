// The PCL detectors keyturn compares against; their templates are not
// precompiled in Debian's PCL, so this is the one translation unit that
// instantiates them.
#include "keyturn/core/keypoint_detectors.h"

#include <pcl/features/normal_3d.h>
#include <pcl/filters/uniform_sampling.h>
#include <pcl/keypoints/harris_3d.h>
#include <pcl/keypoints/sift_keypoint.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include "keyturn/core/error.h"
#include "keyturn/core/radius_search.h"

namespace keyturn {

Detector parseDetector(const std::string& n) {
  if (n == "iss") return Detector::Iss;
  if (n == "harris3d") return Detector::Harris3d;
  if (n == "sift3d") return Detector::Sift3d;
  if (n == "uniform") return Detector::Uniform;
  throw Error("unknown detector '" + n + "' (expected iss, harris3d, sift3d, uniform)");
}

std::string detectorName(Detector d) {
  switch (d) {
    case Detector::Iss: return "iss";
    case Detector::Harris3d: return "harris3d";
    case Detector::Sift3d: return "sift3d";
    case Detector::Uniform: return "uniform";
  }
  return "?";
}

namespace {
pcl::PointCloud<pcl::PointXYZ>::Ptr toPcl(const PointSet& set) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr c(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : set.points) c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return c;
}
}  // namespace

std::vector<Eigen::Vector3f> detectKeypoints(Detector d, const PointSet& set, double res, const DetectorOptions& o) {
  std::vector<Eigen::Vector3f> out;
  if (set.size() < 10) return out;
  switch (d) {
    case Detector::Iss: {
      const RadiusSearch search(set);
      for (int i : detectIssKeypoints(set, search, res, o.iss).keypoints) out.push_back(set.points[i]);
      break;
    }
    case Detector::Harris3d: {
      auto cloud = toPcl(set);
      pcl::HarrisKeypoint3D<pcl::PointXYZ, pcl::PointXYZI> h(pcl::HarrisKeypoint3D<pcl::PointXYZ, pcl::PointXYZI>::HARRIS);
      h.setInputCloud(cloud);
      h.setRadius(o.harris_radius * res);
      h.setNonMaxSupression(true);
      h.setRefine(false);
      h.setNumberOfThreads(1);
      pcl::PointCloud<pcl::PointXYZI> kp;
      h.compute(kp);
      for (const auto& p : kp)
        if (std::isfinite(p.x)) out.emplace_back(p.x, p.y, p.z);
      break;
    }
    case Detector::Sift3d: {
      // SIFT on the surface curvature (PCL's PointNormal field selector picks it).
      auto cloud = toPcl(set);
      pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
      pcl::NormalEstimation<pcl::PointXYZ, pcl::PointNormal> ne;
      ne.setInputCloud(cloud);
      ne.setSearchMethod(tree);
      ne.setRadiusSearch(3.5 * res);
      pcl::PointCloud<pcl::PointNormal>::Ptr pn(new pcl::PointCloud<pcl::PointNormal>);
      ne.compute(*pn);
      for (std::size_t i = 0; i < pn->size(); ++i) {
        (*pn)[i].x = (*cloud)[i].x;
        (*pn)[i].y = (*cloud)[i].y;
        (*pn)[i].z = (*cloud)[i].z;
      }
      pcl::SIFTKeypoint<pcl::PointNormal, pcl::PointWithScale> sift;
      pcl::search::KdTree<pcl::PointNormal>::Ptr tree2(new pcl::search::KdTree<pcl::PointNormal>);
      sift.setSearchMethod(tree2);
      sift.setScales(static_cast<float>(o.sift_min_scale * res), o.sift_octaves, o.sift_scales_per_octave);
      sift.setMinimumContrast(static_cast<float>(o.sift_min_contrast));
      sift.setInputCloud(pn);
      pcl::PointCloud<pcl::PointWithScale> kp;
      sift.compute(kp);
      for (const auto& p : kp) out.emplace_back(p.x, p.y, p.z);
      break;
    }
    case Detector::Uniform: {
      auto cloud = toPcl(set);
      pcl::UniformSampling<pcl::PointXYZ> us;
      us.setInputCloud(cloud);
      us.setRadiusSearch(o.uniform_radius * res);
      pcl::PointCloud<pcl::PointXYZ> kp;
      us.filter(kp);
      for (const auto& p : kp) out.emplace_back(p.x, p.y, p.z);
      break;
    }
  }
  return out;
}

}  // namespace keyturn
