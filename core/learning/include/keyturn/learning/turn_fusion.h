#pragma once
// One object's turn of the table, a view at a time (issue 48): the one home of a turn's answer.
// `classify --fuse`, evaluate's open-set turns and the studio's live fusion only choose which views
// to feed it; the counts, the belief, the answer and the stop are decided here.
// - A view answered "no object" is not a view of the object: it is not counted at all.
// - Closed-set model: every view adds its class evidence (FusionState) and the answer is the
//   belief's class.
// - Open-set model: a view answered "unknown" alone adds no class evidence, and the turn's answer is
//   "unknown" while the mean open-set score of its views (every view of the object, accepted or not)
//   is below the model's turn threshold (OpenSet::thresholdFor: calibrated for the model's stated
//   false-accept rate on turns of left-out categories; a single view's threshold for one view or a
//   model without it). A turn is judged on all it saw: a few end-on views of a known object do not
//   outvote the views that named it, and a mean has no tie for an even count of views. The earlier
//   vote ("unknown" while half the views are) is measured against it in docs/results.md, "Fused turns".
#include <cstddef>
#include <string>
#include <vector>

#include "keyturn/learning/open_set.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

// A turn as evaluate's open-set turns and the turn threshold's calibration read it: this many views
// spread over this many degrees of the table (0°, 45°, 90°).
constexpr int kTurnViews = 3;
constexpr double kTurnSpreadDeg = 90;

// The turns of a set of views: kTurnViews views over kTurnSpreadDeg, one starting at every view whose
// capture group (instance and elevation) has all of them, each a list of indices into the views in
// turntable order. azimuth_deg and group one per view (NaN: no angle, in no turn). evaluate's open-set
// turns, the turn threshold's calibration and `classify --fuse --turns` read turns by it.
std::vector<std::vector<int>> turnsOf(const std::vector<double>& azimuth_deg, const std::vector<std::string>& group);

// One view of a turn as its model answered it alone.
struct TurnView {
  Answer answer = Answer::Class;
  double score = 0;                  // the open-set score (unused by a closed-set model; NaN counts 0)
  std::vector<float> probabilities;  // the classifier's, one per class (may be empty for "no object")
  double azimuth_deg = 0;            // the table's angle
  Matrix pose;                       // poseEvidence, for pose fusion
};

class TurnFusion {
 public:
  // open_set: the model's (its threshold when enabled); options.method decides pose or independent.
  TurnFusion(const FusionOptions& options, const OpenSet& open_set);

  // Throws keyturn::Error as FusionState::add for a view that adds evidence and is malformed.
  void add(const TurnView& view);

  std::size_t views() const { return views_; }           // views of the object, "unknown" ones included
  std::size_t unknownViews() const { return unknown_; }  // answered "unknown" alone
  std::vector<double> belief() const;                    // over the classes; empty before any evidence
  int best() const;                                      // the belief's argmax; -1 before any evidence
  // NoObject before any view of the object; Unknown when no view added evidence or by the open-set
  // rule above; else Class (the class is best()).
  Answer answer() const;
  // The answer is a class whose belief reached options.stop_belief.
  bool certain() const;
  // The belief over the model's classes reached stop_belief while the answer is "unknown".
  bool certainWhileUnknown() const;

 private:
  double topBelief() const;

  FusionOptions options_;
  OpenSet rule_;  // the model's method and thresholds (no references)
  FusionState state_;
  std::size_t views_ = 0, unknown_ = 0;
  double score_sum_ = 0;
};

}  // namespace keyturn::learning
