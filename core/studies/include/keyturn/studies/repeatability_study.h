#pragma once
// A repeatability study over many posed views (docs/repeatability.md): which view
// pairs to compare, a check that the poses make the views overlap at all, each
// detector at its native count and at an equal keypoint budget K, and the scores
// per pair and per detector in Tombari et al.'s terms (absolute and relative
// repeatability against ε in multiples of the resolution).
#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "keyturn/core/report_plot_specs.h"
#include "keyturn/core/cloud.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/error.h"
#include "keyturn/core/keypoint_detectors.h"
#include "keyturn/core/keypoint_placement.h"
#include "keyturn/core/repeatability.h"
#include "keyturn/core/working_resolution.h"

namespace keyturn {

struct StudyView {
  std::string file, group;               // pairs are formed within a group
  double angle_deg = std::nan("");       // turntable angle when known (datasets)
  Eigen::Matrix4d view_from_common = Eigen::Matrix4d::Identity();  // this view's camera ← the common frame
};

// Which views of a group are compared: each with the next by angle, each with the first, or
// every two within a rotation. Written as text in reports: consecutive, from-first, all-within:DEG.
struct PairRule {
  enum class Kind { Consecutive, FromFirst, AllWithin } kind = Kind::Consecutive;
  double within_deg = 360;  // AllWithin's largest rotation between the two views
};
PairRule parsePairRule(const std::string& text);  // throws keyturn::Error naming the text
std::string pairRuleName(const PairRule& rule);   // parsePairRule's text ("all-within:45")

struct StudyOptions {
  std::vector<Detector> detectors{Detector::Iss, Detector::Harris3d, Detector::Sift3d, Detector::Uniform};
  std::vector<double> eps_res{0.5, 1, 1.5, 2, 2.5, 3};  // ε in multiples of the resolution
  PairRule pairs;
  DetectorOptions detector;             // each detector's scales (ISS's also set the budget K)
  bool icp = false;
  bool filter = true;                    // the describe filter before detection
  int keypoints = 0;                     // the equal budget K; 0 = ISS's native count in each view
  double overlap_radius_res = 2.0;       // a point overlaps when the other view has one this close
  double overlap_min = 0.05;             // below: a pair has almost no overlap
  bool force = false;                    // score even when the poses give no overlap
  DepthImageOptions depth;               // how depth-image views are read
  WorkingResolutionOptions working;      // the working resolution iss-chain detects on (describe's)
  KeypointPlacementOptions placement;    // iss-nearest's and iss-salient's settings (placement aside)
};

// Index pairs (model, scene) within each group; datasets' views sorted by angle.
std::vector<std::pair<int, int>> selectPairs(const std::vector<StudyView>& views, const PairRule& rule);
double rotationBetween(const StudyView& a, const StudyView& b);  // degrees

struct PairScore {
  int model = 0, scene = 0;
  double rotation_deg = 0, overlap = 0, icp_rms_m = std::nan("");
  std::vector<double> eps_m;  // ε in metres at the scene's resolution
  std::map<Detector, RepeatabilityResult> native, equal;  // equal: at the budget K
};

struct DetectorSummary {
  double keypoints = 0, equal_keypoints = 0, detection_ms = 0;  // means per view
  std::vector<double> absolute, relative, absolute_equal, relative_equal;  // mean per pair, one per ε
  std::map<int, std::pair<double, int>> relative_by_rotation, relative_equal_by_rotation;  // at ε nearest 2, sum and count
};

struct Study {
  std::vector<StudyView> views;
  std::vector<PairScore> pairs;
  std::map<Detector, DetectorSummary> detectors;
  StudyOptions options;
  double mean_resolution_m = 0, mean_icp_rms_m = std::nan("");
  double mean_overlap = 0, mean_overlap_inverted = std::nan("");  // the latter only when the check failed
  std::size_t eps_near_2 = 0;  // index of the ε closest to 2 × resolution
};

struct StudyProgress {
  std::function<void(const std::string& stage, std::size_t total)> begin = [](const std::string&, std::size_t) {};
  std::function<void()> step = [] {};
  std::function<void()> end = [] {};
};

// Most pairs have almost no overlap under the poses: the message says how many and what the
// inverted poses give; the fields let a front end name its own remedies.
class NoOverlapError : public Error {
 public:
  NoOverlapError(const std::string& message, bool inverse_overlaps) : Error(message), inverse_overlaps(inverse_overlaps) {}
  bool inverse_overlaps;  // the inverted poses do make the views overlap
};

// Loads every view, checks the overlap, detects and scores. Throws NoOverlapError when most
// pairs have almost no overlap, unless options.force; keyturn::Error for a bad view or option.
Study runRepeatabilityStudy(std::vector<StudyView> views, const StudyOptions& options,
                            const StudyProgress& progress = StudyProgress());

// The report's files as text: every pair, detector, budget and ε; each pair's rotation
// and overlap; the summary tables; JSON.
std::string studyCsv(const Study& s);
std::string studyPairsCsv(const Study& s);
std::string studyMarkdown(const Study& s, const std::string& input);
std::string studyJson(const Study& s, const std::string& input);
// Its plots: absolute and relative repeatability against ε, relative against rotation,
// each detector native and at the equal budget ("@K").
ReportPlots studyPlots(const Study& s);

}  // namespace keyturn
