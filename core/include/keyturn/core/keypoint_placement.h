#pragma once
// Where a keypoint found at the working resolution is placed (issue 49). ISS runs on the voxel
// means, and two scans' grids put their means on different surface points, so a keypoint left at
// a mean repeats only at the scale of the working spacing. The placements here keep the chain's
// choice of keypoints (which and how many) and move each onto a measured point:
//  VoxelMeans (default): where ISS found it, on a voxel mean.
//  Nearest: the measured point nearest the mean (the mean's grid error stays).
//  Salient: the measured point of greatest ISS saliency near it, coarse to fine as
//    keypoint_refinement.h does, but each saliency taken from cube moments (the count, mean and
//    scatter of the measured points in each cube of a grid laid on the view's own centroid and
//    principal axes) instead of from every measured neighbour: a cube is counted with a weight
//    that ramps from 1 to 0 over its side around the frame radius, so the saliency changes
//    smoothly as a candidate or the grid moves. Cheap enough to be a default (docs/repeatability.md,
//    "Placing keypoints on measured points").
//  Measured: not a placement of the chain's keypoints but ISS itself run on the measured points at
//    the working scale (measured_keypoints.h): which keypoints and how many may differ.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/iss.h"

namespace keyturn {

enum class KeypointPlacement { VoxelMeans, Nearest, Salient, Measured };
const char* keypointPlacementName(KeypointPlacement p);  // "means", "nearest", "salient", "measured"
KeypointPlacement parseKeypointPlacement(const std::string& name);       // throws keyturn::Error

struct KeypointPlacementOptions {
  KeypointPlacement placement = KeypointPlacement::VoxelMeans;
  // Coarse stage (ISS's radii in multiples of the working resolution s, cubes of side s): the
  // window searched, in ISS suppression radii (half keeps two keypoints' windows disjoint), and
  // at most this many measured candidates in it (every n-th in index order beyond that).
  double window = 0.5;
  int coarse_candidates = 12;
  // Fine stage: radii in multiples of fine_scale × the measured spacing near the keypoints (cubes
  // of that side), its window fine_window × that suppression radius (fine_scale 0: coarse only).
  double fine_scale = 2.0;
  double fine_window = 1.0;
  int fine_candidates = 16;
  // Each stage's cubes, in multiples of its unit (s, or fine_scale × the spacing): larger is cheaper
  // and softer (the frame's edge ramps over one side).
  double cube = 2.0;
};

// The keypoints (positions on the working-resolution view) placed on `measured` (the filtered view
// before the working resolution), distinct points each; as given when measured has fewer than 2
// points, or a keypoint has no measured point near it (and for Measured, which describe detects
// with detectKeypointsOnMeasuredPoints instead). Deterministic.
std::vector<Eigen::Vector3f> placeKeypoints(const PointSet& measured, const std::vector<Eigen::Vector3f>& keypoints,
                                            double working_resolution, const IssOptions& iss,
                                            const KeypointPlacementOptions& options);

}  // namespace keyturn
