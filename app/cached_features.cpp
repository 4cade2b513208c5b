#include "cached_features.h"

#include <iostream>

#include "keyturn/dataset/dataset_layout.h"
#include "keyturn/learning/dataset_features.h"

namespace keyturn::app {

std::vector<dataset::LabelledView> datasetViews(const std::string& root) {
  std::vector<std::string> bad;
  auto views = dataset::datasetViews(root, &bad);
  for (const auto& b : bad) std::cerr << "keyturn: " << dataset::manifestPath(root) << ": skipped " << b << "\n";
  return views;
}

void DescribeProgressLine::begin(std::size_t views) { bar_ = std::make_unique<Progress>("describe", views, !quiet_); }

void DescribeProgressLine::viewDone() { bar_->advance(); }

void DescribeProgressLine::end() { bar_->finish(); }

void DescribeProgressLine::note(const std::string& line) {
  if (!quiet_) std::cerr << "keyturn: " << line << "\n";
}

void DescribeProgressLine::warning(const std::string& line) { std::cerr << "keyturn: " << line << "\n"; }

learning::FeatureTable datasetFeatures(const std::string& dataset, const DescriptorOptions& options, int jobs,
                                       bool quiet, const std::vector<std::string>& feature_sets) {
  DescribeProgressLine progress(quiet);
  std::vector<std::string> blocks;
  for (const auto& set : feature_sets)
    for (const auto& choice : learning::featureSetChoices(set))
      for (const auto& b : learning::featureSetBlocks(choice)) blocks.push_back(b);
  return learning::datasetFeatures({dataset, datasetViews(dataset), options, jobs, &progress},
                                   learning::CacheWrite::Fill, blocks).table;
}

}  // namespace keyturn::app
