#pragma once
// ISS3D keypoints as the paper's §4.2 (after Zhong 2009) defines them:
// density weights w = 1/|N(r_density)|, a weighted scatter matrix about p_i in
// r_frame, eigenvalue-ratio tests λ2/λ1 < γ21 and λ3/λ2 < γ32, saliency λ3 and
// non-maximum suppression in r_nms. Deterministic: the same cloud gives the
// same keypoints in ascending index order.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/radius_search.h"

namespace keyturn {

struct IssOptions {
  // Radii in multiples of the cloud resolution.
  double density_radius = 2.0;
  double frame_radius = 6.0;
  double nms_radius = 3.0;  // chosen by the repeatability sweep (docs/repeatability.md)
  double gamma21 = 0.975;
  double gamma32 = 0.975;
  int min_neighbors = 5;
  // Keypoint budget: at most this many keypoints, the most salient (0 = no cap). The
  // working resolution already bounds K; the budget bounds the K^3 triples of KPD3/KPA3
  // and the K searches of GKPD for whatever input still exceeds it.
  int max_keypoints = 64;
  // The weighted budget (docs/descriptors.md, "Stability"): > 0 gives the budget a soft edge. The
  // most salient (1 − taper)·max_keypoints keypoints weigh 1; below them a keypoint's weight falls
  // linearly with its saliency, to 0 at the saliency of the first keypoint past the budget (0 when
  // none is). A keypoint near the edge then enters and leaves the description gradually, where a
  // hard cut swaps it whole. 0 = the hard budget (every kept keypoint weighs 1).
  double budget_taper = 0.0;
  // A budget that K always reaches (issue 49): when the suppression leaves fewer than max_keypoints
  // maxima, the most salient other points (those the ratio tests turned away ranked by λ3) join,
  // each at least the suppression radius from every keypoint, the radius halved until the budget
  // is met or no point is left. K is then min(max_keypoints, points): the count of a view's local
  // maxima, which sensor noise moves by several, no longer sets it. A filled keypoint weighs 0.3
  // against a maximum's 1 (IssResult::weight; with budget_taper the taper's weights instead).
  bool fill_budget = false;
  // A soft suppression (issue 49): > 0 weighs each local maximum by its margin over the most salient
  // other point within r_nms, 1 − λ3(that point)/λ3(maximum), divided by this and capped at 1. Two
  // nearly equal neighbours, which sensor noise swaps, then both weigh about 0, so the swap moves the
  // PDFs by about nothing where a hard suppression moves a whole keypoint by up to r_nms. Multiplies
  // the budget's weights (filled 0.3, the taper). 0 = every maximum weighs 1.
  double nms_margin = 0.0;
};

struct IssResult {
  std::vector<int> keypoints;     // indices into the PointSet, ascending
  std::vector<double> saliency;   // λ3 per point (0 where the ratio tests failed)
  std::vector<double> weight;     // per keypoint (same order) with a weighted or filled budget; empty otherwise
  int filled = 0;                 // keypoints fill_budget added past the local maxima
};

IssResult detectIssKeypoints(const PointSet& set, const RadiusSearch& search, double resolution,
                             const IssOptions& options);

// ISS's test of one point: the saliency λ3 of its weighted scatter matrix (Eq. 9, already divided
// by the weights' sum) when λ2/λ1 < γ21 and λ3/λ2 < γ32, else 0 — also 0 for a planar or linear patch
// (λ2 or λ3 ≤ 10⁻⁹ λ1: float rounding, not shape). Shared by detection and refinement.
double issSaliency(const Eigen::Matrix3d& scatter, const IssOptions& options);

}  // namespace keyturn
