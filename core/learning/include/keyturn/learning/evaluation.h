#pragma once
// Cross-validated accuracy of one feature set and classifier over a protocol's
// folds: train on each fold's training rows, predict its test rows. Every
// classifier is seeded, so a fold's result does not depend on the thread or the
// process that trains it (evaluate runs folds in parallel and in array jobs).
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/splits.h"
#include "keyturn/learning/training_twins.h"

namespace keyturn::learning {

struct ConfusionCell {
  int truth = 0, predicted = 0, count = 0;
};

// An open-set fold's result for one scoring method (open_set.h): the threshold calibrated on the
// fold's training views and every test view's score.
struct OpenSetFoldOutcome {
  std::string method;
  double threshold = 0;
  std::size_t known_accepted = 0;   // known test views scoring >= threshold
  std::size_t known_correct = 0;    // … and given their true class
  std::size_t unknown_accepted = 0; // unknown views scoring >= threshold (false accepts)
  std::vector<double> known_scores, unknown_scores;
  // Fused over a turn (FoldOutcome::fused_*'s sequences, the open-set rule of view_fusion.h):
  std::size_t fused_known_correct = 0;     // known sequences answered their true class
  std::size_t fused_unknown_accepted = 0;  // unknown sequences given a class
};

struct FoldOutcome {
  std::string name;
  std::size_t train_views = 0, test_views = 0, correct = 0;
  std::size_t twin_views = 0;               // augmentation trained on beside train_views (TwinRows)
  double train_ms = 0, predict_ms = 0;
  std::vector<ConfusionCell> confusion;     // this fold's nonzero [true][predicted] counts
  // A choice made by nested validation (evaluateFoldChoosing): the feature set trained and tested,
  // and each candidate's mean accuracy over the inner folds; empty without a choice.
  std::string chosen;
  std::vector<double> inner_accuracy;
  // Open-set folds (Fold::unknown): the views of the categories left out, and per method the
  // calibrated threshold and scores; test_views and correct are then the known views, closed-set.
  std::size_t unknown_views = 0;
  std::vector<OpenSetFoldOutcome> open_set;
  // … and, where the views have turntable angles, the same views read as sequences of one object
  // turning (kOpenSetFusedViews views over kOpenSetFusedSpreadDeg, open_set_evaluation.h), fused
  // by pose: how many known and unknown sequences, and the known ones right closed-set.
  std::size_t fused_known = 0, fused_unknown = 0, fused_known_closed_correct = 0;
  double accuracy() const { return test_views ? static_cast<double>(correct) / static_cast<double>(test_views) : 0.0; }
};

// A fold's outcome before training: its name and view counts, `train` being the rows it trains on
// (its training views with their twins: withTwins(fold.train, twins)).
FoldOutcome startFoldOutcome(const Fold& fold, const std::vector<std::size_t>& train);

struct Evaluation {
  std::vector<FoldOutcome> folds;
  std::vector<std::vector<int>> confusion;  // [true][predicted], summed over folds
  double mean() const;
  double stddev() const;                    // population spread of the fold accuracies
  double trainMsPerView() const;
  double predictMsPerView() const;
};

// labels: class index per table row (0 .. classes - 1), twins included. One fold trained and
// tested; params as given. twins: each training row's twins are trained on too (none by default).
FoldOutcome evaluateFold(const FeatureTable& table, const std::vector<std::string>& blocks,
                         const std::vector<int>& labels, int classes, const Fold& fold,
                         const ClassifierParams& params, const TwinRows& twins = {});
// The index of the candidate feature set nested validation chooses inside fold `fold` (below), and
// each candidate's mean inner accuracy in `inner_accuracy`.
std::size_t chooseFeatureSet(const FeatureTable& table, const std::vector<std::string>& candidates,
                             const std::vector<int>& labels, int classes, const std::vector<Fold>& folds,
                             std::size_t fold, int max_inner, const ClassifierParams& params, const TwinRows& twins,
                             std::vector<double>& inner_accuracy);
// Chooses among candidate feature sets inside fold `fold` of `folds` (innerFolds, at most
// max_inner): the candidate with the best mean inner accuracy (ties: the first listed) is trained
// on all the fold's training views and tested on its test views, which no choice has seen.
// Inner folds train on the twins of their own training rows only. Throws keyturn::Error when the
// protocol has no other fold to choose on.
FoldOutcome evaluateFoldChoosing(const FeatureTable& table, const std::vector<std::string>& candidates,
                                 const std::vector<int>& labels, int classes, const std::vector<Fold>& folds,
                                 std::size_t fold, int max_inner, const ClassifierParams& params,
                                 const TwinRows& twins = {});
// The folds' confusion cells summed into a classes × classes matrix.
std::vector<std::vector<int>> sumConfusion(const std::vector<FoldOutcome>& folds, int classes);

}  // namespace keyturn::learning
