#pragma once
// PCL's features, keypoints and registration libraries (with what they pull in, ~0.1 s of
// loading: more than the rest of the tool's start-up) are called from the plugin
// "pcl_features" (plugins/pcl_*.cpp), loaded by the first PCL baseline, PCL detector or ICP.
// The table below is its whole interface: plain data in, plain data out. Internal to keyturn_core.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/repeatability.h"

namespace keyturn::detail {

struct PointValue {
  Eigen::Vector3f position;
  float value = 0;
};

struct PclFeatures {
  std::vector<Eigen::Vector3f> (*iss_keypoints)(const PointSet& set, double frame_radius, double nms_radius,
                                                double gamma21, double gamma32, int min_neighbors);
  std::vector<float> (*esf)(const PointSet& set);
  std::vector<float> (*esf_seeded)(const PointSet& set, unsigned seed);
  std::vector<float> (*our_cvfh)(const PointSet& set, double normal_radius);  // in this process
  std::vector<float> (*vfh)(const PointSet& set, double normal_radius);
  // Harris3D (HARRIS response, radius in metres, one thread, no refinement): the keypoints with
  // PCL's non-maximum suppression, or without it every point PCL reports, with its response.
  std::vector<PointValue> (*harris)(const PointSet& set, double radius, bool non_max_suppression);
  // PCL's surface curvature at every point, normals from a radius search.
  std::vector<float> (*curvature)(const PointSet& set, double normal_radius);
  // SIFT3D on the curvature of normals from a radius search (scales in metres).
  std::vector<Eigen::Vector3f> (*sift)(const PointSet& set, double normal_radius, float min_scale, int octaves,
                                       int scales_per_octave, float min_contrast);
  IcpRefinement (*icp)(const std::vector<Eigen::Vector3f>& model, const std::vector<Eigen::Vector3f>& scene,
                       const Eigen::Matrix4d& initial, double max_distance, int iterations);
};

// The plugin's table (loaded on the first call). Throws keyturn::Error when it cannot be loaded.
const PclFeatures& pclFeatures();

using PclFeaturesFunction = const PclFeatures*();

}  // namespace keyturn::detail
