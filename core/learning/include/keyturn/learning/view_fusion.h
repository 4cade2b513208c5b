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

// The belief after each view. Throws keyturn::Error for an empty sequence, views with differing
// class counts, or pose fusion of a view without pose evidence.
FusedSequence fuseViews(const std::vector<FusionView>& views, const FusionOptions& options);

}  // namespace keyturn::learning
