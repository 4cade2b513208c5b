#include "dataset_features.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <mutex>
#include <regex>
#include <set>
#include <thread>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/pcl_baselines.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/rig/dataset.h"
#include "progress.h"

namespace keyturn::app {

namespace fs = std::filesystem;
using learning::FeatureRow;
using learning::FeatureTable;

namespace {

using learning::kNormalRadius;
const std::vector<Feature> kKeypointBlocks = {Feature::KPD2, Feature::KPD3, Feature::KPA3,
                                              Feature::GKPD1, Feature::GKPD2, Feature::GKPCD2};
const std::vector<Feature> kShapeBlocks = {Feature::D2, Feature::D3, Feature::A3};

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}


FeatureTable emptyTable(const DescriptorFlags& flags) {
  FeatureTable t;
  for (Feature f : kKeypointBlocks) t.blocks.push_back(featureName(f)), t.sizes.push_back(flags.options.histogram.bins);
  for (Feature f : kShapeBlocks) t.blocks.push_back(featureName(f)), t.sizes.push_back(flags.options.histogram.bins);
  for (Feature f : kKeypointBlocks) t.blocks.push_back("u_" + featureName(f)), t.sizes.push_back(flags.options.histogram.bins);
  t.blocks.insert(t.blocks.end(), {"esf", "vfh", "ourcvfh"});
  t.sizes.insert(t.sizes.end(), {640, 308, 308});
  t.spec = featureSpec(flags);
  return t;
}

void put(FeatureRow& row, const FeatureTable& t, const std::string& block, const std::vector<double>& v) {
  const int o = t.offset(block);
  for (std::size_t k = 0; k < v.size(); ++k) row.values[static_cast<std::size_t>(o) + k] = static_cast<float>(v[k]);
}

void note(FeatureRow& row, const std::string& what) { row.problem += (row.problem.empty() ? "" : "; ") + what; }

// Every block of one view. A block that cannot be computed stays NaN and the
// row says why: the view stays in every protocol, so all features are judged
// on the same views.
// The descriptor options of every cached view: all keypoint and shape blocks,
// the random-keypoint twin; filtering is done by the caller (the peers share it).
DescriptorOptions cacheOptions(const DescriptorFlags& flags) {
  DescriptorOptions o = flags.toOptions();
  o.features = kKeypointBlocks;
  o.features.insert(o.features.end(), kShapeBlocks.begin(), kShapeBlocks.end());
  o.random_keypoints_twin = true;
  o.random_seed = o.osada.seed;
  return o;
}

FeatureRow describeCloud(const Cloud& cloud, const DescriptorOptions& options, const DescriptorFlags& flags,
                         const FeatureTable& layout) {
  FeatureRow row;
  row.values.assign(static_cast<std::size_t>(layout.width()), std::nanf(""));
  row.keypoints = -1;
  const Cloud filtered = options.filter ? filterCloud(cloud, options.filter_options) : cloud;
  DescriptorOptions o = options;
  o.filter = false;
  try {
    const ViewDescriptor d = describeView(filtered, o);
    row.keypoints = d.keypointCount();
    for (std::size_t f = 0; f < o.features.size(); ++f) {
      put(row, layout, featureName(o.features[f]), d.pdfs[f]);
      if (isKeypointFeature(o.features[f])) put(row, layout, "u_" + featureName(o.features[f]), d.random_keypoint_pdfs[f]);
    }
    if (d.low_keypoints) note(row, "only " + std::to_string(row.keypoints) + " keypoints");
  } catch (const Error& e) {
    note(row, e.what());
  }
  const PointSet set = PointSet::fromCloud(filtered);
  if (set.size() < 10) {
    note(row, "peers skipped: " + std::to_string(set.size()) + " points");
    return row;
  }
  const auto copy = [&](const std::string& block, const std::function<std::vector<float>()>& compute) {
    try {
      const std::vector<float> v = compute();
      if (v.empty()) return note(row, block + " found nothing");
      put(row, layout, block, std::vector<double>(v.begin(), v.end()));
    } catch (const Error& e) {
      note(row, block + ": " + e.what());
    }
  };
  copy("esf", [&] { return pclEsfSeeded(set, static_cast<unsigned>(flags.options.osada.seed)); });
  copy("vfh", [&] { return pclVfh(set, kNormalRadius); });
  copy("ourcvfh", [&] { return pclOurCvfh(set, kNormalRadius); });
  return row;
}

struct ViewRef {
  std::string id, file, cls, instance, elevation;
};

std::vector<ViewRef> datasetViews(const std::string& root) {
  if (!fs::is_regular_file(fs::path(root) / "manifest.csv"))
    throw Error(root + ": not a keyturn dataset (no manifest.csv)");
  std::vector<std::string> bad;
  std::vector<ViewRef> out;
  for (const auto& r : rig::Dataset::readManifest(root, &bad)) {
    ViewRef v;
    for (const auto& f : r.files)
      if (f.size() > 4 && f.compare(f.size() - 4, 4, ".pcd") == 0) v.file = f;
    if (v.file.empty()) continue;
    v.id = v.file.substr(0, v.file.size() - 4);
    v.cls = r.key.cls;
    v.instance = r.key.instance;
    v.elevation = r.key.elevation;
    out.push_back(v);
  }
  for (const auto& b : bad) std::cerr << "keyturn: " << root << "/manifest.csv: skipped " << b << "\n";
  if (out.empty()) throw Error(root + ": the dataset has no views");
  return out;
}

// Describes views[i] for the given indices, in parallel, with progress.
std::vector<FeatureRow> describeViews(const std::string& root, const std::vector<ViewRef>& views,
                                      const std::vector<std::size_t>& which, const DescriptorFlags& flags,
                                      const FeatureTable& layout, int jobs, bool quiet) {
  std::vector<FeatureRow> rows(which.size());
  const DescriptorOptions options = cacheOptions(flags);
  Progress progress("describe", which.size(), !quiet);
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t k = next++; k < which.size(); k = next++) {
      const ViewRef& v = views[which[k]];
      const std::string path = (fs::path(root) / v.file).string();
      try {
        rows[k] = describeCloud(loadCloud(path), options, flags, layout);
      } catch (const Error& e) {
        rows[k].values.assign(static_cast<std::size_t>(layout.width()), std::nanf(""));
        rows[k].keypoints = -1;
        rows[k].problem = e.what();
      }
      rows[k].id = v.id;
      rows[k].cls = v.cls;
      rows[k].instance = v.instance;
      rows[k].elevation = v.elevation;
      progress.advance();
    }
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const unsigned n = jobs > 0 ? static_cast<unsigned>(jobs) : hw;
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::min<std::size_t>(n, which.size()); ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  progress.finish();
  return rows;
}

}  // namespace

std::map<std::string, std::string> featureSpec(const DescriptorFlags& f) { return learning::featureSpec(f.options); }

std::string cachePath(const std::string& dataset, const DescriptorFlags& flags, int shard, int shards) {
  std::string key;
  for (const auto& [k, v] : featureSpec(flags)) key += k + "=" + v + "\n";
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
  std::string name = std::string("features-") + hash;
  if (shards > 1) name += ".shard-" + std::to_string(shard + 1) + "-of-" + std::to_string(shards);
  return (fs::path(dataset) / ".keyturn" / (name + ".csv")).string();
}

std::string describeDatasetShard(const CacheRequest& r) {
  if (r.shards < 1 || r.shard < 0 || r.shard >= r.shards)
    throw Error("--shard " + std::to_string(r.shard + 1) + "/" + std::to_string(r.shards) + ": expected I/N with 1 <= I <= N");
  const auto views = datasetViews(r.dataset);
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < views.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(r.shards)) == r.shard) mine.push_back(i);
  FeatureTable t = emptyTable(r.flags);
  t.rows = describeViews(r.dataset, views, mine, r.flags, t, r.jobs, r.quiet);
  const std::string path = cachePath(r.dataset, r.flags, r.shard, r.shards);
  fs::create_directories(fs::path(path).parent_path());
  learning::saveFeatureTable(path, t);
  return path;
}

FeatureTable loadOrDescribeDataset(const CacheRequest& r) {
  const auto views = datasetViews(r.dataset);
  const std::string path = cachePath(r.dataset, r.flags);
  FeatureTable t = emptyTable(r.flags);
  std::error_code ec;
  if (fs::exists(path, ec)) {
    try {
      t = learning::loadFeatureTable(path);
    } catch (const Error& e) {
      std::cerr << "keyturn: " << e.what() << " — describing the views again\n";
      t = emptyTable(r.flags);
    }
  } else {
    // Shards from an array job: merge a complete set.
    const std::string stem = fs::path(path).stem().string();
    std::map<int, std::vector<std::string>> sets;
    const std::regex shard_re(stem + R"(\.shard-(\d+)-of-(\d+)\.csv)");
    for (const auto& e : fs::directory_iterator(fs::path(path).parent_path(), ec)) {
      std::smatch m;
      const std::string name = e.path().filename().string();
      if (std::regex_match(name, m, shard_re)) sets[std::stoi(m[2])].push_back(e.path().string());
    }
    for (auto& [n, files] : sets) {
      if (static_cast<int>(files.size()) != n) continue;
      std::sort(files.begin(), files.end());
      std::vector<FeatureTable> shards;
      for (const auto& f : files) shards.push_back(learning::loadFeatureTable(f));
      t = learning::mergeFeatureTables(shards, files);
      if (!r.quiet) std::cerr << "keyturn: merged " << n << " feature shards\n";
      break;
    }
  }
  if (t.blocks != emptyTable(r.flags).blocks || t.spec != featureSpec(r.flags)) t = emptyTable(r.flags);
  // Keep cached rows of views still in the manifest; describe the rest.
  std::map<std::string, FeatureRow> have;
  for (auto& row : t.rows) have[row.id] = std::move(row);
  std::vector<std::size_t> missing;
  for (std::size_t i = 0; i < views.size(); ++i)
    if (!have.count(views[i].id)) missing.push_back(i);
  if (!missing.empty()) {
    auto rows = describeViews(r.dataset, views, missing, r.flags, t, r.jobs, r.quiet);
    for (auto& row : rows) have[row.id] = std::move(row);
  }
  t.rows.clear();
  for (const auto& v : views) t.rows.push_back(std::move(have[v.id]));
  if (!missing.empty() || !fs::exists(path, ec)) {
    fs::create_directories(fs::path(path).parent_path());
    learning::saveFeatureTable(path, t);
  }
  return t;
}

FeatureTable describeFiles(const std::vector<std::string>& files, const DescriptorFlags& flags, int jobs, bool quiet,
                           std::vector<std::string>* errors) {
  std::vector<ViewRef> views;
  for (const auto& f : files) views.push_back({f, f, "?", "?", "?"});
  std::vector<std::size_t> all(views.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  FeatureTable t = emptyTable(flags);
  t.rows = describeViews("", views, all, flags, t, jobs, quiet || files.size() < 2);
  if (errors)
    for (const auto& row : t.rows)
      if (row.keypoints < 0) errors->push_back(row.id + ": " + row.problem);
  return t;
}

}  // namespace keyturn::app
