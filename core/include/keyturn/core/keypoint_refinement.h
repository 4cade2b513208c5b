#pragma once
// Keypoints found at the working resolution, placed on the measured surface (issue 30).
// The working resolution puts every point at a voxel mean, and two scans' grids (each laid on its
// own view) put their means on different surface points: a keypoint can only sit where a mean is,
// so it repeats only at the scale of the working spacing. Refinement keeps the chain's choice of
// keypoints (which and how many: its stability) and moves each one, coarse to fine, to the
// measured point of greatest ISS saliency near it: first at the chain's own scale, then at the
// sensor's (radii in multiples of fine_scale × the measured spacing), which depend on the surface
// and not on the grid (docs/repeatability.md, "Real scans with true poses").
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/iss.h"

namespace keyturn {

struct KeypointRefinementOptions {
  bool enabled = false;
  // The window searched around each keypoint, in multiples of ISS's suppression radius: half of it
  // keeps the windows of two keypoints (at least r_nms apart) disjoint, so they stay distinct.
  double window = 0.5;
  // The second, fine stage: ISS's radii in multiples of fine_scale × the measured points' mean
  // spacing near the keypoints, its window fine_window × that r_nms (0 = the first stage only).
  // Chosen on the Stanford scans (docs/repeatability.md): 1× the spacing is too fine to rank
  // saliency on a scan's noise, 3× too coarse to place it.
  double fine_scale = 2.0;
  double fine_window = 1.0;
};

// For each keypoint (a position found on the working-resolution view), the measured point within
// window × r_nms of it whose ISS saliency λ3 — its weighted scatter in r_frame, density weights in
// r_density, the radii in multiples of `working_resolution` as the chain used them — is greatest and
// passes ISS's ratio tests (the keypoint as it was when no measured point there does); then the same
// at the fine scale around that point. Ties go to the lower index. Deterministic; `measured` is the
// filtered view before the working resolution.
std::vector<Eigen::Vector3f> refineKeypointsOnMeasuredPoints(const PointSet& measured,
                                                             const std::vector<Eigen::Vector3f>& keypoints,
                                                             double working_resolution, const IssOptions& iss,
                                                             const KeypointRefinementOptions& options);

namespace detail {
// The weighted scatters of the refinement take an AVX2 path where the CPU has it: the scalar loop's
// sums up to the order of addition. true forces the scalar loop (tests and benchmarks compare them).
void useScalarScatter(bool scalar);
// Whether the scatters take the AVX2 path now (the CPU has AVX2 and it is not switched off).
bool scatterUsesAvx2();
}  // namespace detail

}  // namespace keyturn
