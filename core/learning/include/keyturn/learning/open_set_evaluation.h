#pragma once
// keyturn evaluate's open-set protocol (docs/results.md, "Open-set answers"): one fold trains on
// the known categories' training views, calibrates each open-set method's threshold on those
// views alone (open_set_calibration.h: categories left out in turn), and tests the known
// categories' held-out views (closed-set accuracy; accepted and right) and every view of the
// categories left out (unknowns: how many are accepted).
#include <vector>

#include "keyturn/learning/evaluation.h"
#include "keyturn/learning/open_set_calibration.h"

namespace keyturn::learning {

// fold.unknown must not be empty; labels: class index per table row (twins included).
FoldOutcome evaluateOpenSetFold(const FeatureTable& table, const std::vector<std::string>& blocks,
                                const std::vector<int>& labels, const Fold& fold, const ClassifierParams& params,
                                const OpenSetOptions& options, const TwinRows& twins = {});

// A row's open-set figures over its folds, one per method (the folds' order of methods).
struct OpenSetSummary {
  std::string method;
  double auroc_mean = 0, auroc_sd = 0;        // known vs unknown, per fold
  double false_accept = 0;                    // unknowns accepted / unknowns, all folds
  double known_accuracy_open = 0;             // known views accepted with their true class / known views
  double known_accuracy_closed = 0;           // known views given their true class (no rejection)
  double known_rejected = 0;                  // known views rejected / known views
  std::size_t known_views = 0, unknown_views = 0;
  std::vector<double> known_scores, unknown_scores;  // all folds, for the ROC curve
};
std::vector<OpenSetSummary> summariseOpenSet(const std::vector<FoldOutcome>& folds);

}  // namespace keyturn::learning
