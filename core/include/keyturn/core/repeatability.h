#pragma once
// Keypoint repeatability between two views of one object (the paper's §4.2,
// Fig 10; after Tombari et al.): the model view's keypoints are carried into the
// scene view by the ground-truth transform; one is *visible* when a scene point
// lies within 1 × resolution of it; the *absolute repeatability* at ε is the
// number of visible keypoints whose nearest scene keypoint lies within ε, the
// *relative repeatability* that number over the visible ones.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"

namespace keyturn {

struct RepeatabilityResult {
  int model_keypoints = 0, scene_keypoints = 0, visible = 0;
  std::vector<int> absolute;      // one per ε
  std::vector<double> relative;   // one per ε (0 when nothing is visible)
};

// eps in metres; scene_from_model maps model-view coordinates into the scene view.
RepeatabilityResult keypointRepeatability(const std::vector<Eigen::Vector3f>& model_keypoints,
                                          const std::vector<Eigen::Vector3f>& scene_keypoints,
                                          const PointSet& scene_points, double scene_resolution,
                                          const Eigen::Matrix4d& scene_from_model, const std::vector<double>& eps_m,
                                          double visibility_radius_res = 1.0);

// Fraction of a's points (at most max_points of them, evenly strided) that have a
// point of b within radius once carried by b_from_a: how much the two views overlap.
double overlapFraction(const PointSet& a, const PointSet& b, const Eigen::Matrix4d& b_from_a, double radius_m,
                       std::size_t max_points = 2000);

struct IcpRefinement {
  Eigen::Matrix4d scene_from_model = Eigen::Matrix4d::Identity();
  double rms_m = 0;     // of the final correspondences
  bool converged = false;
};

// PCL IterativeClosestPoint from the initial guess, correspondences up to max_distance.
IcpRefinement refineByIcp(const PointSet& model, const PointSet& scene, const Eigen::Matrix4d& initial,
                          double max_distance, int iterations = 50);

}  // namespace keyturn
