#pragma once
// keyturn evaluate's next-best-view protocol (docs/results.md, "Next best view"): for each fold of
// a group-wise protocol (leave-instance, leave-elevation), the classifier and pose references are
// fitted on the training views, and the classifier's per-angle behaviour (next_best_view.h) is
// estimated by the same protocol run inside the training views (inner folds; a class no inner fold
// holds out gets the fold classifier's answers on its own training views). Each held-out capture
// group is then read as sequences from each start view: the next best view chosen after every view,
// beside fixed steps, all fused by pose; accuracy after n views, and the stopping rule at a sweep
// of belief thresholds (accuracy against the mean number of views taken).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "keyturn/core/report_plot_specs.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/fusion_evaluation.h"
#include "keyturn/learning/next_best_view.h"

namespace keyturn::learning {

struct NbvEvaluationOptions {
  FusionOptions fusion;  // the method is pose (the belief over rotations NBV reads); bin_deg, floor
  std::vector<FusionSchedule> fixed;         // the fixed steps compared (the first is the target's)
  int max_views = 6;
  int target_views = 3;                      // the fixed schedule's accuracy after this many views is the target
  // Turns NBV may choose: every step, from step to 360° − step. 45°, not finer: neighbouring views
  // err alike, which the per-angle table does not model (docs/results.md, "Next best view").
  double candidate_step_deg = 45;
  double tolerance_deg = 2.5;                // a wanted azimuth matches a view this close
  double likelihood_window_deg = 45;         // ViewLikelihoodOptions::window_deg
  std::vector<double> stop_beliefs = {0.9, 0.95, 0.99, 0.999, 0.9999};
  int start_every = 1;                       // sequences start at every k-th view of a held-out group
};

inline const char* kNextBestViewPolicy = "next best view";

// Accuracy after n views of one policy ("next best view" or a fixed schedule's name).
struct ViewCountCurve {
  std::string policy;
  std::vector<std::size_t> sequences, correct;  // [n - 1]
  double accuracy(std::size_t n) const;         // n from 1; NaN without sequences
};

// One policy under the stopping rule at one threshold: views taken until the belief reaches it
// (max_views when it never does).
struct StoppingPoint {
  std::string policy;
  double stop_belief = 0;
  std::size_t sequences = 0, correct = 0, views = 0;  // views summed over sequences
  double accuracy() const;
  double meanViews() const;
};

struct NbvProtocolResult {
  std::string protocol, label_kind;
  std::size_t folds = 0, test_views = 0, single_view_correct = 0;
  std::vector<ViewCountCurve> curves;        // next best view first, then each fixed schedule
  std::vector<StoppingPoint> stopping;       // per policy, per threshold
  std::map<int, std::size_t> first_turns;    // NBV's second view: turn (degrees) → sequences
  double target() const;                     // the first fixed schedule's accuracy after target_views
  int target_views = 0;
};

// The least mean number of views with which `policy` under the stopping rule reaches `accuracy`
// (NaN when no threshold does).
double viewsToReach(const NbvProtocolResult& result, const std::string& policy, double accuracy);

// The table's rows' azimuths as evaluateFusion takes them. Throws keyturn::Error for a protocol
// other than leave-instance or leave-elevation, a size mismatch, no fixed schedule, fewer than 2
// views, a target beyond max_views, or a protocol without folds.
NbvProtocolResult evaluateNextBestView(const FeatureTable& table, const std::vector<double>& azimuth_deg,
                                       const std::vector<std::string>& blocks, const std::string& protocol,
                                       const ClassifierParams& params, const NbvEvaluationOptions& options,
                                       int jobs = 0);

struct NbvReport {
  std::string json, markdown, csv;
  ReportPlots plots;
};
NbvReport nbvReport(const std::vector<NbvProtocolResult>& results, const std::string& dataset,
                    const std::string& features, const std::string& classifier, const NbvEvaluationOptions& options);

}  // namespace keyturn::learning
