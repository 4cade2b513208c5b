#pragma once
// The parameters that shape a view's feature vector, and their text form kept
// in feature caches and model sidecars ("bins" → "32", …). One mapping in both
// directions, so a live recogniser computes exactly the features its model was
// trained on.
#include <map>
#include <string>
#include <vector>

#include "keyturn/core/descriptor.h"

namespace keyturn::learning {

constexpr int kFeatureCacheVersion = 3;     // 2: 9 significant digits (exact); 3: support rule, working resolution
constexpr double kNormalRadius = 0.012;     // VFH / OUR-CVFH normals, metres (≈ 4 SR4000 pixels at 0.6 m)

struct FeatureParams {
  int bins = 32;
  std::string range = "fixed";  // fixed | per-view
  double extent = 0.35;         // metres, fixed ranges
  bool filter = true;
  bool plane_removal = true;
  double max_range = 3.0;
  double jump_edge_angle = 10.0;  // degrees, 0 = off
  double iss_frame = 6.0, iss_nms = 4.0, iss_density = 2.0;  // × resolution
  double graph_radius = 3.5;
  double samples_across = WorkingResolutionOptions().samples_across;  // 0 = the sensor's own resolution
  int max_keypoints = IssOptions().max_keypoints;                     // 0 = no budget
  int osada_samples = 20000;
  unsigned long long seed = 7;
};

std::map<std::string, std::string> featureSpec(const FeatureParams& p);
// Throws keyturn::Error naming `source` and the key for a missing or bad entry,
// or a cache version other than this build's.
FeatureParams featureParamsFromSpec(const std::map<std::string, std::string>& spec, const std::string& source);
// Throws keyturn::Error for non-positive radii or an unknown range rule.
DescriptorOptions descriptorOptions(const FeatureParams& p, const std::vector<Feature>& features);

}  // namespace keyturn::learning
