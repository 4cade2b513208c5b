#pragma once
// Multi-view fusion (issue 34, docs/results.md "Multi-view fusion"): the belief over classes after
// each view of one object as the turntable turns it, each view's azimuth known.
// - independent: belief ∝ Π_i p_i(c), the classifier's probabilities of the views multiplied
//   (log-probabilities summed; poses unused).
// - pose: the classifier's evidence plus a pose-consistency term: for each class, the best
//   rotation φ of the sequence's relative azimuths Δθ_i against the class's training views,
//   max_φ Σ_i −d_i(c, φ + Δθ_i)² / (2σ²), d_i(c, a) the RMS distance (standardised features)
//   from view i to the nearest training view of class c in the azimuth bin of a. The views must
//   match the class's views at angles as far apart as theirs are, so shuffled poses score lower.
// The belief after view n is normalised (sums to 1); a sequence stops at the first view whose
// highest belief reaches the stated threshold.
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

// "independent", "pose" (in the order reports list them).
const std::vector<std::string>& fusionMethods();
// Throws keyturn::Error naming the method when it is not one of fusionMethods().
void checkFusionMethod(const std::string& method);

struct FusionOptions {
  std::string method = "pose";
  double stop_belief = 0.99;        // stop once the highest fused belief reaches this
  double probability_floor = 1e-4;  // a class probability below it counts as it (one wrong view cannot veto)
  double bin_deg = 5;               // the azimuth bins of the pose term (the turntable's step)
};

// Each class's training views by azimuth, standardised as the knn open-set score standardises.
struct PoseReferences {
  int classes = 0;
  int bins = 72;                 // 360° / bin_deg
  std::vector<float> mean, scale;
  Matrix references;             // standardised training views (rows)
  std::vector<int> reference_class;
  std::vector<int> reference_bin;
  double sigma = 1;              // the pose term's distance scale (see fitPoseReferences)
  bool empty() const { return references.rows() == 0; }
};

// x: training rows; y: class indices; azimuth_deg: each row's turntable angle; group: each row's
// capture group (instance and elevation), used only to set sigma: the median distance from a
// training view to the nearest view of its class in another group at the same azimuth bin (how
// far a view is from its class seen another way). Throws keyturn::Error for mismatched sizes or a
// bin width that does not divide 360° into at least 4 bins.
PoseReferences fitPoseReferences(const Matrix& x, const std::vector<int>& y, const std::vector<double>& azimuth_deg,
                                 const std::vector<std::string>& group, int classes, double bin_deg);

// One view's pose evidence: classes × bins, −d(c, bin)² / (2σ²) (an empty bin of a class takes
// its circularly nearest non-empty bin's value; a class without training views −∞).
Matrix poseEvidence(const PoseReferences& refs, const Eigen::RowVectorXf& x);

// One view of a sequence as fusion sees it.
struct FusionView {
  std::vector<float> probabilities;  // the classifier's, one per class
  double azimuth_deg = 0;            // the turntable's angle when the view was taken
  Matrix pose;                       // poseEvidence (empty for independent fusion)
};

struct FusedSequence {
  std::vector<std::vector<double>> belief;  // after each view, one per class, summing to 1
  std::vector<int> best;                    // the argmax of each belief
  std::size_t stopped_after = 0;            // views until the highest belief reached the threshold (all if never)
};

// The evidence of one sequence so far, a view at a time: fuseViews adds each view of a sequence,
// next best view (next_best_view.h) reads the belief between views to choose the next angle.
class FusionState {
 public:
  explicit FusionState(const FusionOptions& options);  // throws for an unknown method
  // Throws keyturn::Error for a view whose class count differs from the first's, a view without an
  // azimuth, or (pose fusion) a view without pose evidence; `index` names the view in the message.
  void add(const FusionView& view, std::size_t index);
  std::size_t views() const { return views_; }
  std::size_t classes() const { return evidence_.size(); }
  double firstAzimuth() const { return first_azimuth_; }
  // Over the classes, summing to 1 (pose fusion: each class at its best rotation).
  std::vector<double> belief() const;
  // Pose fusion only: over (class c, rotation φ) — [c][φ], φ the training views' azimuth bin of the
  // sequence's first view — the classifier's evidence of c plus the pose term at φ, normalised over
  // all pairs (sums to 1). Throws keyturn::Error for independent fusion or before any view.
  std::vector<std::vector<double>> jointBelief() const;

 private:
  FusionOptions options_;
  bool pose_ = false;
  std::size_t views_ = 0;
  int bins_ = 0;
  double first_azimuth_ = 0;
  std::vector<double> evidence_;                // summed floored log-probabilities, per class
  std::vector<std::vector<double>> aligned_;    // [c][φ]: Σ_i pose(c, φ + Δθ_i)
};

// The belief after each view. Throws keyturn::Error for an empty sequence, views with differing
// class counts, or pose fusion of a view without pose evidence.
FusedSequence fuseViews(const std::vector<FusionView>& views, const FusionOptions& options);

}  // namespace keyturn::learning
