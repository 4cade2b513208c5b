#pragma once
// A dataset's feature cache as the commands use it: the views of its manifest
// (keyturn_dataset) described by learning::datasetFeatures, progress and notes on stderr.
#include <memory>
#include <string>
#include <vector>

#include "keyturn/core/descriptor.h"
#include "keyturn/dataset/dataset_views.h"
#include "keyturn/learning/feature_cache.h"
#include "progress.h"

namespace keyturn::app {

using dataset::isDataset;  // a keyturn dataset folder: one holding manifest.csv

// Throws keyturn::Error for a folder without a manifest or views; skipped rows are reported.
std::vector<dataset::LabelledView> datasetViews(const std::string& dataset);

// stderr: a progress line (unless quiet), notes (unless quiet) and warnings.
class DescribeProgressLine final : public learning::DescribeProgress {
 public:
  explicit DescribeProgressLine(bool quiet) : quiet_(quiet) {}
  void begin(std::size_t views) override;
  void viewDone() override;
  void end() override;
  void note(const std::string& line) override;
  void warning(const std::string& line) override;

 private:
  bool quiet_;
  std::unique_ptr<Progress> bar_;
};

// `feature_sets`: the sets the caller reads ("kpd2+kpa3", "a|b"); an older cache gains the blocks of
// them it lacks (learning::FeatureCache::needs).
learning::FeatureTable datasetFeatures(const std::string& dataset, const DescriptorOptions& options, int jobs,
                                       bool quiet, const std::vector<std::string>& feature_sets = {});

}  // namespace keyturn::app
