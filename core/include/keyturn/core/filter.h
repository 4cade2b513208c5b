#pragma once
// §4.1 filtering of a depth view: range/box crop, jump-edge removal, support
// plane removal (RANSAC + the support rule), largest-cluster segmentation and
// statistical outlier removal. Each step is optional. The input's kind is
// recognised (docs/filtering.md): a full organized frame with a support
// (SR4000, Kinect, RealSense), an organized frame already masked to the object,
// or an unorganized, already segmented object cloud; the defaults suit all three.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/working_resolution.h"

namespace keyturn {

struct FilterOptions {
  // Range crop on the distance from the camera (metres); <= 0 disables a bound.
  bool crop_range = true;
  float min_range = 0.1f;
  float max_range = 3.0f;
  // Axis-aligned box crop in the camera frame, off by default.
  bool crop_box = false;
  Eigen::Vector3f box_min{-1.f, -1.f, 0.f};
  Eigen::Vector3f box_max{1.f, 1.f, 3.f};

  // Jump edges (mixed pixels): a pixel with one 8-neighbour nearly straight in
  // front of it and another nearly straight behind it (segments within this
  // angle of its viewing ray) is removed. Organized clouds only.
  bool jump_edge = true;
  float jump_edge_angle_deg = 10.0f;

  // Support plane (table/turntable): the dominant RANSAC plane (inliers at least
  // this fraction of the points) is removed, with everything behind it, only when
  // it is a support the object stands on — the points it does not explain lie on
  // the camera's side of it and its inliers spread at least as wide as those
  // points' footprint on it. A face of the object (the rest lies behind it) or a
  // plate's floor (its rim spreads wider) is kept.
  bool remove_plane = true;
  float plane_distance = 0.008f;
  // > 0: after the object's cluster is found (with the fixed band), the points between this many
  // robust σ of the support's inliers (median absolute distance × 1.4826, within [plane_min_band,
  // plane_distance]) and plane_distance that connect to the object through steps of plane_regrow
  // are put back: a frame's own noise decides how much of an object's foot goes with the table
  // (reconstruction: the scissors' 16 mm lost their lower 8 mm to the fixed band). 0: describe's
  // fixed band.
  float plane_band_sigmas = 0.f;
  float plane_min_band = 0.001f;
  float plane_regrow = 0.004f;
  float plane_min_fraction = 0.15f;
  int plane_iterations = 200;
  int plane_max_samples = 5000;    // RANSAC hypotheses scored on at most this many points
  int support_min_points = 30;     // points above a support: fewer and it is not holding anything

  // Keep only the largest Euclidean cluster (the object), cluster tolerance in metres.
  bool largest_cluster = true;
  float cluster_tolerance = 0.015f;

  // Statistical outlier removal (PCL): mean k-NN distance beyond mean + std_mul*σ.
  bool outlier_removal = true;
  int sor_k = 12;
  float sor_std_mul = 2.0f;
};

// What kind of input the filter was given (reported, and it decides which steps apply:
// the range crop and jump edges need an organized frame in the camera's coordinates).
enum class InputKind { Frame, MaskedFrame, SegmentedCloud };
const char* inputKindName(InputKind kind);  // "frame", "masked-frame", "segmented-cloud"

// One step's effect: points before and after it. `flagged` marks a step that removed
// more than half of what it was given where that is not its job (see filterCloud).
struct FilterStep {
  std::string name;  // crop, jump-edges, support-plane, cluster, outliers (and working-resolution)
  bool applied = false;
  std::size_t before = 0, after = 0;
  bool flagged = false;
  std::string note;  // why a step did not apply, or what it decided
  std::size_t removed() const { return before - after; }
};

struct FilterReport {
  InputKind kind = InputKind::SegmentedCloud;
  std::vector<FilterStep> steps;  // in the order they ran
  std::size_t input_valid = 0;  // after points beyond kMaxCoordinate were made invalid (before any step)
  std::size_t too_far = 0;      // those points: no measurement (radius_search.h)
  std::size_t after_crop = 0;
  std::size_t after_jump_edge = 0;
  std::size_t after_plane = 0;
  std::size_t after_cluster = 0;
  std::size_t after_outliers = 0;
  bool plane_found = false;
  Eigen::Vector4f plane{0.f, 0.f, 0.f, 0.f};  // ax+by+cz+d=0, normal towards the camera
  float plane_band = 0.f;                      // the height above it removed with it (metres)
  bool anyFlagged() const;
  std::string flaggedSummary() const;  // "support-plane removed 93% (12563 of 12575)", …; empty when none
};

// An organized frame with fewer valid pixels than this fraction is taken to be masked to the object.
constexpr double kMaskedFrameMaxValidFraction = 0.3;
InputKind classifyInput(const Cloud& cloud);

// Returns a cloud of the same layout (organized stays organized, removed points NaN).
// With `working`, the view is also brought to the working resolution, as the step before the
// outlier removal (whose statistics are then those of the working spacing, and cheap);
// `before_working` then receives the view as that step found it (the measured points keypoint
// refinement places keypoints on: keypoint_refinement.h).
Cloud filterCloud(const Cloud& input, const FilterOptions& options, FilterReport* report = nullptr,
                  const WorkingResolutionOptions* working = nullptr, WorkingResolutionReport* working_report = nullptr,
                  Cloud* before_working = nullptr);

// Individual steps, each keeping the layout.
void cropRange(Cloud& cloud, float min_range, float max_range);
void cropBox(Cloud& cloud, const Eigen::Vector3f& box_min, const Eigen::Vector3f& box_max);
std::size_t removeJumpEdges(Cloud& cloud, float angle_deg);
// Removes the dominant plane when it is a support (see FilterOptions). `decision`, when given,
// says what was found and why it was or was not removed; `band`, the height above the plane
// removed with it. Returns whether it was removed.
bool removeDominantPlane(Cloud& cloud, const FilterOptions& options, Eigen::Vector4f* plane,
                         std::string* decision = nullptr, float* band = nullptr);
void keepLargestCluster(Cloud& cloud, float tolerance);

namespace detail {
// How many of the points (x, y, z) lie strictly within `threshold` of the plane (a, b, c, d):
// the count PCL's SampleConsensusModelPlane::countWithinDistance gives, point for point (tested),
// in a loop over rows the compiler vectorises. The plane step's RANSAC scores its hypotheses by it.
std::size_t countPlaneInliers(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z,
                              const Eigen::Vector4f& plane, double threshold);
}  // namespace detail
// PCL's StatisticalOutlierRemoval rule, point for point (a test compares them): a point goes when
// its mean distance to its k nearest neighbours exceeds the mean of those means by std_mul standard
// deviations. The neighbours' squared distances are exactly those PCL's FLANN k-d tree gives, all
// found at once from a hash grid (nearestSquaredDistances): PCL's filter as keyturn called it took
// 9.6 ms for the 2,054 points of the built-in view, the tree searched in one batch 1.6 ms, the grid
// 1.1 ms (docs/benchmarks.md, "The filter's own steps" and "The live set on the real crops").
void removeStatisticalOutliers(Cloud& cloud, int k, float std_mul);

}  // namespace keyturn
