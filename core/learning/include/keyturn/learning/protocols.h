#pragma once
// An evaluation protocol over a feature table (docs/results.md): its folds and
// the label each row is judged by — instances for k-fold, leave-one-elevation-out
// and fixed lists unless told otherwise, categories for leave-one-instance-out — and the statistics
// of a table that reports quote (keypoint counts, missing blocks, per-class PDFs).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/splits.h"

namespace keyturn::learning {

enum class LabelKind { Instance, Category };

struct Labels {
  LabelKind kind = LabelKind::Instance;
  std::vector<std::string> names;  // sorted
  std::vector<int> of_row;         // index into names, one per table row
  std::string kindName() const { return kind == LabelKind::Category ? "category" : "instance"; }
};

// Throws keyturn::Error for a name other than instance or category.
LabelKind parseLabelKind(const std::string& name);
Labels labelRows(const FeatureTable& table, LabelKind kind);

struct Protocol {
  std::string name;
  std::vector<Fold> folds;
  Labels labels;
};

// kfoldN (shuffled with seed), leave-elevation, leave-instance, fixed:FILE (one test view id
// per line, ".pcd" optional, '#' comments). Throws keyturn::Error naming a bad name or file.
// `label` overrides the protocol's own (instance; category for leave-instance), except that
// leave-instance is always judged by category: its test instance is never trained on.
Protocol makeProtocol(const std::string& name, const FeatureTable& table, std::uint64_t seed,
                      std::optional<LabelKind> label = std::nullopt);

struct TableSummary {
  std::size_t views = 0, low = 0, failed = 0;  // low: K < low_keypoints; failed: no keypoint features
  int k_min = 0, k_median = 0, k_max = 0;
  std::map<std::string, std::size_t> missing;  // block → views without it
};
TableSummary summarise(const FeatureTable& table, int low_keypoints);

// Mean and population sd of a block's PDF over one class's views (views without the block left out).
struct ClassPdf {
  std::string label;
  int views = 0;
  std::vector<double> mean, sd;
};
// One per label with at least one view; empty when the table lacks the block.
std::vector<ClassPdf> classPdfs(const FeatureTable& table, const Labels& labels, const std::string& block);

}  // namespace keyturn::learning
