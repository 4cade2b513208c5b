#pragma once
// Open-set answers (issue 34): a score per view saying how much it looks like the trained
// classes, and the threshold below which the answer is "unknown" instead of a class.
// Three scores (docs/results.md, "Open-set answers", measures them):
// - max-probability: the classifier's own highest class probability;
// - knn: 1 / (1 + d), d the RMS per-feature distance (features standardised by the training
//   views' mean and spread, a missing value at the mean) from the view to the nearest
//   `neighbours` training views of the class the classifier chose (their mean distance);
// - knn-relative: the same with d divided by the chosen class's own scale, the median distance
//   from one of its training views to the nearest other (small noisy objects lie farther from
//   their training views than large ones, known or not). With scale_by "camera" (the default of
//   train since issue 47), d is also divided by the view's camera's own factor: how far that camera's
//   training views lie from their nearest neighbour, relative to their class's scale (the SR4000's
//   sparser, noisier views lie farther than the OpenNI2's). docs/results.md, "Beyond the training
//   conditions", measures it against the one pooled scale and other levers. With class_scale_power
//   p < 1, each class's scale is drawn toward the median class's (s_c^p · median^(1-p)): a class whose
//   own views lie far apart (the thin screwdriver's, 4 × the median's) otherwise lends that spread to
//   every unknown view it is chosen for. With class_spread "instances", a class of several instances
//   (a category model's) is scaled by how far its instances' views lie from each other's (the nearest
//   view of another instance), so a view of an instance it never saw is judged by the spread between
//   instances, not by the sensor noise between neighbouring views of one.
// The distance d (knn, knn-relative) is the RMS of the standardised differences ("rms") or one between
// the rows as described, PDF blocks only: "l1" (the sum of their L1 distances, each within [0, 2]) or
// "chi2" (½Σ(p−q)²/(p+q), each within [0, 1]). Standardising weighs a PDF bin by its spread over the
// training views, so the sparse tail bins that a few keypoint pairs move weigh most; L1 and χ² weigh
// the mass that moves, χ² relative to the mass there (docs/results.md, "The open-set distance").
// Higher is more like a trained class for all three; a view is accepted when score >= threshold.
// The threshold is calibrated (open_set_calibration.h) for a stated false-accept rate on
// views of categories the classifier never saw.
#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

// What a view is: one of the model's classes, "unknown" (unlike every trained class: its open-set
// score is below the model's threshold) or "no object" (too little in view to describe).
enum class Answer { Class, Unknown, NoObject };
std::string answerName(Answer answer);  // "class", "unknown", "no object"

// The methods a score can come from, in the order reports list them.
const std::vector<std::string>& openSetMethods();
// Throws keyturn::Error naming the method when it is not one of openSetMethods().
void checkOpenSetMethod(const std::string& method);
// Whether the method's scorer keeps the standardised training views (knn, knn-relative).
bool keepsReferences(const std::string& method);
// The distances a knn score can measure: rms, l1 (OpenSet::distance).
const std::vector<std::string>& openSetDistances();
// Throws keyturn::Error naming the distance when it is not one of openSetDistances().
void checkOpenSetDistance(const std::string& distance);
// As above, and l1 or chi2 (which compare PDFs) over a block that is not a PDF (size, a peer) too.
void checkOpenSetDistanceFor(const std::string& distance, const std::vector<std::string>& blocks);
// Throws keyturn::Error when a method that measures distances to references (knn, knn-relative) is
// asked over the keypoints themselves ("kpset"): their order is describe's, not a feature's.
void checkOpenSetMethodsFor(const std::vector<std::string>& methods, const std::vector<std::string>& blocks);

struct OpenSet {
  std::string method;          // "" : closed-set (every view gets a class)
  double threshold = 0;        // accepted when score >= threshold
  double false_accept = 0;     // the stated rate the threshold was calibrated for
  int calibration_views = 0;   // unknown views the threshold was set on
  int calibration_groups = 0;  // trainings, each without one group of categories
  // How the threshold meets the stated rate (openSetRules()): "pooled", on all the left-out views
  // together; "per-group", on each left-out group's views alone (the strictest group's threshold).
  std::string rule = "pooled";
  // A turn's threshold (turn_fusion.h): the mean score of a turn's views accepted when >= it,
  // calibrated for the same false-accept rate on turns of the left-out categories' capture groups
  // (kTurnViews views over kTurnSpreadDeg, as evaluate reads turns). NaN: not calibrated (a model
  // trained before it, or on views without angles): a turn takes the single view's threshold.
  double turn_threshold = std::nan("");
  int calibration_turns = 0;
  // The threshold a turn of `views` views is held to: a single view's for one view, else the turn's.
  double thresholdFor(std::size_t views) const {
    return views > 1 && std::isfinite(turn_threshold) ? turn_threshold : threshold;
  }
  // knn: the training views, standardised (rows), their class, and the standardisation.
  int neighbours = 1;
  std::string distance = "rms";  // rms or l1 (above); a model file without one measured rms
  std::vector<float> mean, scale;
  Matrix references;
  std::vector<int> reference_class;
  std::vector<float> class_scale;  // knn-relative: per class, the distance d is divided by
  // knn-relative: the power p the class scales were drawn toward their median by (1: each class's own).
  double class_scale_power = 1;
  // knn-relative: "pooled" (the class scale alone) or "camera" (times the view's camera's factor).
  std::string scale_by = "pooled";
  // knn-relative: "views" (a class's scale from the nearest other view of it) or "instances" (a class
  // of several instances scaled by the nearest view of another instance; one of a single instance by
  // its own views' scale times the median such ratio). Fitting only: the scales are stored.
  std::string class_spread = "views";
  // scale_by "camera": per camera (cameraOf, feature_cache.h: the organized grid "WxH"), the median over
  // its training views of (distance to the nearest other view of the class) / (the class's scale).
  std::map<std::string, float> camera_scale;
  // The factor a view of `camera` is scaled by: 1 for the pooled scale, an unknown or "" camera.
  float cameraFactor(const std::string& camera) const {
    const auto it = camera_scale.find(camera);
    return scale_by == "camera" && it != camera_scale.end() ? it->second : 1.f;
  }
  bool enabled() const { return !method.empty(); }
  // Class when score >= threshold (or closed-set), else Unknown (a NaN score too).
  Answer answerFor(double score) const { return !enabled() || score >= threshold ? Answer::Class : Answer::Unknown; }
};

// The ways knn-relative scales a view's distance: pooled, camera (open_set.h's scale_by).
const std::vector<std::string>& openSetScales();
// Throws keyturn::Error naming the scale when it is not one of openSetScales().
void checkOpenSetScale(const std::string& scale_by);
// The calibration rules (OpenSet::rule): pooled, per-group.
const std::vector<std::string>& openSetRules();
// Throws keyturn::Error naming the rule when it is not one of openSetRules().
void checkOpenSetRule(const std::string& rule);
// The spreads a class's knn-relative scale is measured by: views, instances (OpenSet::class_spread).
const std::vector<std::string>& openSetSpreads();
// Throws keyturn::Error naming the spread when it is not one of openSetSpreads().
void checkOpenSetSpread(const std::string& spread);

// A scorer for `method` fitted on training rows x (labels y: class indices): knn keeps the
// standardised rows; max-probability keeps nothing. threshold and calibration are left at 0.
// scale_by "camera" (knn-relative) fits a factor per camera of `cameras` (one per row; rows of ""
// count for no camera); without cameras it is the pooled scale. class_scale_power (knn-relative, within
// [0, 1]): each class's scale s_c becomes s_c^p · median^(1-p), the median over the classes' scales
// (the upper middle of an even count; 1: its own; 0: one scale for all, the knn score over a constant); the camera factors are taken
// against those scales. class_spread "instances" (knn-relative) needs `instances` (one per row): each
// class's scale is then multiplied by its instances' spread over its views' (camera factors unchanged).
// Throws keyturn::Error for a power outside [0, 1], an unknown spread or instances not one per row.
OpenSet fitOpenSetScorer(const std::string& method, const Matrix& x, const std::vector<int>& y, int neighbours = 1,
                         const std::string& scale_by = "pooled", const std::vector<std::string>* cameras = nullptr,
                         double class_scale_power = 1, const std::string& class_spread = "views",
                         const std::vector<std::string>* instances = nullptr, const std::string& distance = "rms");

// The distance between two standardised rows as the scorer measures it (its `distance`).
double openSetDistance(const OpenSet& scorer, const Eigen::RowVectorXf& a, const Eigen::RowVectorXf& b);

// One score per row of x (probabilities: the classifier's rows for x; cameras: each row's camera, or
// none: every view at the pooled scale). A row whose score cannot be computed (non-finite
// probabilities, no reference of its class) scores 0.
std::vector<double> openSetScores(const OpenSet& scorer, const Matrix& x, const Matrix& probabilities,
                                  const std::vector<std::string>* cameras = nullptr);

// The threshold that accepts at most a fraction `false_accept` of these scores of unknown
// views (score >= threshold): the smallest score above the highest rejected one. Throws
// keyturn::Error when there are no scores or the rate is outside [0, 1).
double thresholdForFalseAccept(std::vector<double> unknown_scores, double false_accept);

// The area under the ROC curve of known (positive) against unknown scores, ties counted half;
// NaN when either list is empty.
double auroc(const std::vector<double>& known, const std::vector<double>& unknown);

// The ROC curve: false-accept rate (unknowns accepted) against true-accept rate (knowns
// accepted) at every distinct score, from (0, 0) to (1, 1).
struct RocCurve {
  std::vector<double> false_accept, true_accept;
};
RocCurve rocCurve(const std::vector<double>& known, const std::vector<double>& unknown);

}  // namespace keyturn::learning
