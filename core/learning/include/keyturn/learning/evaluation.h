#pragma once
// Cross-validated accuracy of one feature set and classifier over a protocol's
// folds: train on each fold's training rows, predict its test rows. Folds run
// on worker threads; every classifier is seeded, so results do not depend on
// the scheduling.
#include <functional>
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/splits.h"

namespace keyturn::learning {

struct FoldOutcome {
  std::string name;
  std::size_t train_views = 0, test_views = 0, correct = 0;
  double train_ms = 0, predict_ms = 0;
  double accuracy() const { return test_views ? static_cast<double>(correct) / static_cast<double>(test_views) : 0.0; }
};

struct Evaluation {
  std::vector<FoldOutcome> folds;
  std::vector<std::vector<int>> confusion;  // [true][predicted], summed over folds
  double mean() const;
  double stddev() const;                    // population spread of the fold accuracies
  double trainMsPerView() const;
  double predictMsPerView() const;
};

// labels: class index per table row (0 .. classes - 1).
Evaluation evaluateFolds(const FeatureTable& table, const std::vector<std::string>& blocks,
                         const std::vector<int>& labels, int classes, const std::vector<Fold>& folds,
                         const ClassifierParams& params, int jobs,
                         const std::function<void()>& fold_done = nullptr);

}  // namespace keyturn::learning
