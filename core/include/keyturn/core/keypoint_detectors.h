#pragma once
// 3-D keypoint detectors compared in repeatability tests, each with its scale
// in multiples of the cloud resolution: keyturn's ISS3D, PCL's HarrisKeypoint3D,
// SIFTKeypoint on surface curvature, and uniform sampling as the floor.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/iss.h"

namespace keyturn {

// IssChain is ISS as `describe` runs it: on the view brought to the working resolution
// (working_resolution.h), its radii in multiples of that view's resolution. The detectors here
// treat it as Iss; the repeatability study hands it the working-resolution view. IssRefined is
// IssChain's keypoints moved onto the measured points (keypoint_refinement.h), as the chain places
// them when DescriptorOptions::refine is on; IssNearest and IssSalient IssChain's keypoints placed
// as DescriptorOptions::placement places them (keypoint_placement.h: nearest, salient). IssChain
// itself is placed as describe's default placement does, so that it is what describe outputs.
// IssMeasured is ISS run on the measured points at the chain's scale (radii in multiples of the
// working resolution), as DescriptorOptions::placement "measured" detects them.
enum class Detector { Iss, Harris3d, Sift3d, Uniform, IssChain, IssRefined, IssNearest, IssSalient, IssMeasured };

// iss, harris3d, sift3d, uniform, iss-chain, iss-refined, iss-nearest, iss-salient, iss-measured; throws keyturn::Error
Detector parseDetector(const std::string& name);
std::string detectorName(Detector d);
// ISS, on the raw view or on the chain's (every detector but Harris3d, SIFT and uniform sampling).
inline bool isIssOnSomeView(Detector d) { return d != Detector::Harris3d && d != Detector::Sift3d && d != Detector::Uniform; }
// ISS on describe's working-resolution view, whatever its placement.
inline bool isChainDetector(Detector d) { return isIssOnSomeView(d) && d != Detector::Iss; }

struct DetectorOptions {
  IssOptions iss;             // radii in multiples of the resolution
  double harris_radius = 6.0;  // × resolution
  double sift_min_scale = 2.0; // × resolution
  int sift_octaves = 4;
  int sift_scales_per_octave = 4;
  double sift_min_contrast = 0.0;  // curvature differences are small; any extremum counts
  double uniform_radius = 6.0; // × resolution
};

// Keypoint positions on the (filtered) point set, in its frame.
std::vector<Eigen::Vector3f> detectKeypoints(Detector d, const PointSet& set, double resolution,
                                             const DetectorOptions& options = DetectorOptions());

// Exactly min(k, set size) keypoints for comparing detectors at one budget: the
// detector's own keypoints (ISS without its cap) ranked by its saliency — ISS λ3,
// Harris's response, for SIFT the surface curvature it runs on at the nearest
// point — and the first k kept. When it finds fewer, the rest are the most salient
// other points at least the detector's suppression radius from those chosen (the
// radius halved until k are found). Uniform sampling has no saliency: its points in
// farthest-point order from the one nearest the centroid, completed the same way.
std::vector<Eigen::Vector3f> detectKeypointsAtBudget(Detector d, const PointSet& set, double resolution, int k,
                                                     const DetectorOptions& options = DetectorOptions());

}  // namespace keyturn
