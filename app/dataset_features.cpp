#include "dataset_features.h"

#include <filesystem>
#include <iostream>

#include "keyturn/rig/dataset_views.h"

namespace keyturn::app {

bool isDataset(const std::string& path) {
  return std::filesystem::is_regular_file(std::filesystem::path(path) / "manifest.csv");
}

std::vector<learning::LabelledView> datasetViews(const std::string& root) {
  std::vector<std::string> bad;
  auto views = rig::datasetViews(root, &bad);
  for (const auto& b : bad) std::cerr << "keyturn: " << root << "/manifest.csv: skipped " << b << "\n";
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
                                       bool quiet) {
  DescribeProgressLine progress(quiet);
  return learning::loadOrDescribeCache({dataset, datasetViews(dataset), options, jobs, &progress});
}

}  // namespace keyturn::app
