#pragma once
// keyturn evaluate's open-set protocol (docs/results.md, "Open-set answers"): one fold trains on
// the known categories' training views, calibrates each open-set method's threshold on those
// views alone (open_set_calibration.h: categories left out in turn), and tests the known
// categories' held-out views (closed-set accuracy; accepted and right) and every view of the
// categories left out (unknowns: how many are accepted).
#include <vector>

#include "keyturn/learning/evaluation.h"
#include "keyturn/learning/open_set_calibration.h"
#include "keyturn/learning/turn_fusion.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

// The turn the fused figures read: this many views spread evenly over this many degrees of
// one capture group (instance and elevation), starting at each of its views (the fusion target's
// schedule, docs/results.md "Multi-view fusion").
constexpr int kOpenSetFusedViews = kTurnViews;
constexpr double kOpenSetFusedSpreadDeg = kTurnSpreadDeg;

// One turn as evaluate's open-set turns read it (a TurnFusion fed every view, each answered by its
// score under `scorer`; a closed-set scorer answers every view), fused by pose unless options say
// otherwise: the fused class, -1 for unknown.
int fusedTurnClass(const std::vector<FusionView>& views, const std::vector<double>& scores, const OpenSet& scorer,
                   const FusionOptions& options = FusionOptions());

// fold.unknown must not be empty; labels: class index per table row (twins included).
// azimuth_deg: each table row's turntable angle (NaN: none); when given, the known and unknown
// views are also read as turning sequences and fused by pose (FoldOutcome::fused_*): closed-set,
// and per method with the open-set rule (turn_fusion.h, TurnFusion).
FoldOutcome evaluateOpenSetFold(const FeatureTable& table, const std::vector<std::string>& blocks,
                                const std::vector<int>& labels, const Fold& fold, const ClassifierParams& params,
                                const OpenSetOptions& options, const TwinRows& twins = {},
                                const std::vector<double>& azimuth_deg = {});

// A row's open-set figures over its folds, one per method (the folds' order of methods).
struct OpenSetSummary {
  std::string method;
  double auroc_mean = 0, auroc_sd = 0;        // known vs unknown, per fold
  double false_accept = 0;                    // unknowns accepted / unknowns, all folds
  std::vector<double> false_accept_by_fold;   // the same, fold by fold (NaN: a fold without unknowns)
  double known_accuracy_open = 0;             // known views accepted with their true class / known views
  double known_accuracy_closed = 0;           // known views given their true class (no rejection)
  double known_rejected = 0;                  // known views rejected / known views
  std::size_t known_views = 0, unknown_views = 0;
  std::vector<double> known_scores, unknown_scores;  // all folds, for the ROC curve
  // Fused over kOpenSetFusedViews views (NaN without sequences): as above, per sequence.
  std::size_t fused_known = 0, fused_unknown = 0;
  double fused_false_accept = 0, fused_known_accuracy_open = 0, fused_known_accuracy_closed = 0;
};
std::vector<OpenSetSummary> summariseOpenSet(const std::vector<FoldOutcome>& folds);

}  // namespace keyturn::learning
