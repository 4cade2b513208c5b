#include "dataset_features.h"

#include <iostream>

#include "keyturn/rig/dataset_views.h"

namespace keyturn::app {

std::vector<learning::LabelledView> datasetViews(const std::string& root) {
  return rig::datasetViews(root, [&root](const std::string& row) {
    std::cerr << "keyturn: " << root << "/manifest.csv: skipped " << row << "\n";
  });
}

void DescribeProgressLine::begin(std::size_t views) { bar_ = std::make_unique<Progress>("describe", views, !quiet_); }

void DescribeProgressLine::viewDone() { bar_->advance(); }

void DescribeProgressLine::end() { bar_->finish(); }

void DescribeProgressLine::note(const std::string& line) {
  if (!quiet_) std::cerr << "keyturn: " << line << "\n";
}

void DescribeProgressLine::warning(const std::string& line) { std::cerr << "keyturn: " << line << "\n"; }

learning::FeatureTable datasetFeatures(const std::string& dataset, const DescriptorOptions& options, int jobs,
                                       bool quiet) {
  DescribeProgressLine progress(quiet);
  return learning::loadOrDescribeCache({dataset, datasetViews(dataset), options, jobs, &progress});
}

}  // namespace keyturn::app
