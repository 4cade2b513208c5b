#include "dataset_features.h"

#include <filesystem>
#include <iostream>

#include "keyturn/core/error.h"
#include "keyturn/rig/dataset.h"

namespace keyturn::app {

namespace fs = std::filesystem;

std::vector<learning::LabelledView> datasetViews(const std::string& root) {
  if (!fs::is_regular_file(fs::path(root) / "manifest.csv"))
    throw Error(root + ": not a keyturn dataset (no manifest.csv)");
  std::vector<std::string> bad;
  std::vector<learning::LabelledView> out;
  for (const auto& r : rig::Dataset::readManifest(root, &bad)) {
    const std::string pcd = r.pcd();
    if (pcd.empty()) continue;
    out.push_back({pcd.substr(0, pcd.size() - 4), (fs::path(root) / pcd).string(), r.key.cls, r.key.instance,
                   r.key.elevation});
  }
  for (const auto& b : bad) std::cerr << "keyturn: " << root << "/manifest.csv: skipped " << b << "\n";
  if (out.empty()) throw Error(root + ": the dataset has no views");
  return out;
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
