#pragma once
// Training-side augmentation (evaluate --train-extra): another rendering of a
// dataset's views — the same view ids, each seen with its own jitter of
// distance, elevation, tilt and integration time (keyturn simulate --jitter) —
// whose rows are trained on only where the view they re-render is. A fold that
// tests a view therefore never trains on its twin, under every protocol, and
// nested validation's inner folds are held to the same rule.
#include <cstddef>
#include <string>
#include <vector>

#include "keyturn/learning/feature_table.h"

namespace keyturn::learning {

// Per row of the original table, the rows appended for it (its twins); empty: no augmentation.
using TwinRows = std::vector<std::vector<std::size_t>>;

// Appends extra's rows to table and returns each original row's twins. Throws keyturn::Error
// naming extra_name for other blocks or descriptor parameters, a view id that no original row has,
// or a twin whose class or instance differs from its original's.
TwinRows appendTwins(FeatureTable& table, const FeatureTable& extra, const std::string& extra_name);

// rows and, after them, the twins of each (the rows a fold trains on once augmented).
std::vector<std::size_t> withTwins(const std::vector<std::size_t>& rows, const TwinRows& twins);

// labels (one per original row) extended to the twins: a twin is judged by its original's label.
std::vector<int> labelsWithTwins(std::vector<int> labels, const TwinRows& twins);

}  // namespace keyturn::learning
