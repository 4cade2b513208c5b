#include "keyturn/learning/feature_cache.h"

#include <algorithm>
#include <chrono>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/depth_scale_check.h"
#include "keyturn/core/empty_view.h"
#include "keyturn/core/error.h"
#include "keyturn/core/fnv1a.h"
#include "keyturn/core/parallel_for.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/pcl_baselines.h"
#include "keyturn/core/plugin.h"
#include "keyturn/dataset/feature_cache_files.h"
#include "keyturn/learning/feature_spec.h"

namespace keyturn::learning {

namespace fs = std::filesystem;

namespace {

const std::vector<Feature> kKeypointBlocks = {Feature::KPD2, Feature::KPD3, Feature::KPA3,
                                              Feature::GKPD1, Feature::GKPD2, Feature::GKPCD2};
const std::vector<Feature> kShapeBlocks = {Feature::D2, Feature::D3, Feature::A3};
const std::map<std::string, int> kPeerSizes = {{"esf", 640}, {"vfh", 308}, {"ourcvfh", 308}};
const std::string kRandom = "u_";  // a keypoint block on random keypoints
const std::string kScaled = "s_";  // a length block in RMS radii of the view (view_size.h)
const std::string kSize = "size";  // the view's RMS radius and spreads (metres)
const std::string kKeypointSet = "kpset";  // the keypoints themselves (keypointSetBlock)

bool has(const FeatureTable& t, const std::string& block) { return t.offset(block) >= 0; }

void put(FeatureRow& row, const FeatureTable& t, const std::string& block, const std::vector<double>& v) {
  const int o = t.offset(block);
  if (o < 0) return;
  for (std::size_t k = 0; k < v.size(); ++k) row.values[static_cast<std::size_t>(o) + k] = static_cast<float>(v[k]);
}

void note(FeatureRow& row, const std::string& what) { row.problem += (row.problem.empty() ? "" : "; ") + what; }

// The descriptor options that compute the layout's keypoint and shape blocks: a u_ block needs its
// keypoint function and the random-keypoint twin. The filter stays as the options say: the keypoint
// blocks go through describeView's filter and working resolution, as `describe` and the recogniser's do.
DescriptorOptions optionsFor(const FeatureTable& layout, const DescriptorOptions& options) {
  DescriptorOptions o = options;
  o.features.clear();
  o.random_keypoints_twin = false;
  o.scaled_twin = false;
  o.random_seed = options.osada.seed;
  for (Feature f : allFeatures()) {
    const bool random = isKeypointFeature(f) && has(layout, kRandom + featureName(f));
    const bool scaled = has(layout, kScaled + featureName(f));
    if (has(layout, featureName(f)) || random || scaled) o.features.push_back(f);
    o.random_keypoints_twin = o.random_keypoints_twin || random;
    o.scaled_twin = o.scaled_twin || scaled;
  }
  // The size block or the keypoints alone still need the view described (its points, after the filter).
  if (o.features.empty() && (has(layout, kSize) || has(layout, kKeypointSet))) o.features.push_back(Feature::KPD2);
  return o;
}

}  // namespace

std::string cameraOf(const Cloud& cloud) {
  return cloud.organized() ? std::to_string(cloud.width) + "x" + std::to_string(cloud.height) : std::string();
}

FeatureRow describeCloud(const Cloud& cloud, const DescriptorOptions& options, const FeatureTable& layout) {
  FeatureRow row;
  row.camera = cameraOf(cloud);
  row.values.assign(static_cast<std::size_t>(layout.width()), std::nanf(""));
  row.keypoints = -1;
  const DescriptorOptions o = optionsFor(layout, options);
  // The keypoint blocks through the one view path (filter, working resolution), as describe and the
  // recogniser see a view; the peers (ESF, VFH, OUR-CVFH) on the filtered points at the sensor's own
  // density, as their users run them.
  if (!o.features.empty()) {
    try {
      const ViewDescriptor d = describeView(cloud, o);
      row.keypoints = d.keypointCount();
      for (std::size_t f = 0; f < o.features.size(); ++f) {
        put(row, layout, featureName(o.features[f]), d.pdfs[f]);
        if (!d.random_keypoint_pdfs.empty() && isKeypointFeature(o.features[f]))
          put(row, layout, kRandom + featureName(o.features[f]), d.random_keypoint_pdfs[f]);
        if (!d.scaled_pdfs.empty()) put(row, layout, kScaled + featureName(o.features[f]), d.scaled_pdfs[f]);
      }
      put(row, layout, kSize, d.size.block());
      put(row, layout, kKeypointSet, keypointSetBlock(d.keypoints));
      if (d.low_keypoints) note(row, "only " + std::to_string(row.keypoints) + " keypoints");
    } catch (const EmptyViewError& e) {
      row.no_object = true;
      note(row, e.what());
    } catch (const InstallError&) {
      throw;
    } catch (const Error& e) {
      note(row, e.what());
    }
  }
  const bool peers = has(layout, "esf") || has(layout, "vfh") || has(layout, "ourcvfh");
  if (!peers) return row;
  const PointSet set = PointSet::fromCloud(options.filter ? filterCloud(cloud, options.filter_options) : cloud);
  if (set.size() < 10) {
    note(row, "peers skipped: " + std::to_string(set.size()) + " points");
    return row;
  }
  const auto copy = [&](const std::string& block, const std::function<std::vector<float>()>& compute) {
    if (!has(layout, block)) return;
    try {
      const std::vector<float> v = compute();
      if (v.empty()) return note(row, block + " found nothing");
      put(row, layout, block, std::vector<double>(v.begin(), v.end()));
    } catch (const InstallError&) {
      throw;
    } catch (const Error& e) {
      note(row, block + ": " + e.what());
    }
  };
  copy("esf", [&] { return pclEsfSeeded(set, static_cast<unsigned>(options.osada.seed)); });
  copy("vfh", [&] { return pclVfh(set, kNormalRadius); });
  copy("ourcvfh", [&] { return pclOurCvfh(set, kNormalRadius); });
  return row;
}

namespace {

// The views `which` described (progress counts each; begin and end are the caller's).
std::vector<FeatureRow> describeRows(const std::vector<LabelledView>& views, const std::vector<std::size_t>& which,
                                     const DescriptorOptions& options, const FeatureTable& layout, int jobs,
                                     DescribeProgress* progress) {
  std::vector<FeatureRow> rows(which.size());
  parallelFor(which.size(), jobs, [&](std::size_t k) {
    const LabelledView& v = views[which[k]];
    try {
      const Cloud cloud = loadCloud(v.path, v.depth);
      // A wrong depth scale empties the view too, but it is the user's to fix, not "no object".
      if (options.filter && isDepthImagePath(v.path)) checkDepthScale("", cloud, v.depth.depth_scale, options.filter_options);
      rows[k] = describeCloud(cloud, options, layout);
    } catch (const InstallError&) {
      throw;  // the machine's, not the view's: a cached row would keep it for every run after
    } catch (const Error& e) {
      rows[k].values.assign(static_cast<std::size_t>(layout.width()), std::nanf(""));
      rows[k].keypoints = -1;
      rows[k].problem = e.what();
    }
    rows[k].id = v.id;
    rows[k].cls = v.cls;
    rows[k].instance = v.instance;
    rows[k].elevation = v.elevation;
    if (progress) progress->viewDone();
  });
  return rows;
}

std::vector<FeatureRow> describeSome(const std::vector<LabelledView>& views, const std::vector<std::size_t>& which,
                                     const DescriptorOptions& options, const FeatureTable& layout, int jobs,
                                     DescribeProgress* progress) {
  if (progress) progress->begin(which.size());
  std::vector<FeatureRow> rows = describeRows(views, which, options, layout, jobs, progress);
  if (progress) progress->end();
  return rows;
}

void save(const std::string& path, const FeatureTable& t) {
  fs::create_directories(fs::path(path).parent_path());
  saveFeatureTable(path, t);
}

// The merged rows of a complete set of shard files of the cache with this hash, if there is one.
bool mergeShards(const std::string& root, const std::string& hash, FeatureTable& out, DescribeProgress* progress) {
  for (auto& [n, files] : dataset::featureCacheShards(root, hash)) {
    if (static_cast<int>(files.size()) != n) continue;
    std::vector<FeatureTable> shards;
    for (const auto& f : files) shards.push_back(loadFeatureTable(f));
    out = mergeFeatureTables(shards, files);
    if (progress) progress->note("merged " + std::to_string(n) + " feature shards");
    return true;
  }
  return false;
}

// The cache's name for these options: a hash of their feature specification.
std::string specHash(const DescriptorOptions& options) {
  std::string key;
  for (const auto& [k, v] : featureSpec(options)) key += k + "=" + v + "\n";
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
  return hash;
}

}  // namespace

BlockName parseBlockName(const std::string& name) {
  if (kPeerSizes.count(name)) return {BlockName::Peer};
  if (name == kKeypointSet) return {BlockName::KeypointSet};
  if (name == kSize) return {BlockName::Size};
  BlockName b;
  std::string feature = name;
  if (name.rfind(kRandom, 0) == 0) b.kind = BlockName::RandomTwin, feature = name.substr(kRandom.size());
  if (name.rfind(kScaled, 0) == 0) b.kind = BlockName::ScaledTwin, feature = name.substr(kScaled.size());
  try {
    b.feature = parseFeature(feature);
  } catch (const Error&) {
    throw Error("unknown block '" + name + "'");
  }
  if ((b.kind == BlockName::RandomTwin && !isKeypointFeature(b.feature)) ||
      (b.kind == BlockName::ScaledTwin && isAngleFeature(b.feature)))
    throw Error("unknown block '" + name + "' (" +
                (b.kind == BlockName::RandomTwin ? "u_ twins are of keypoint functions" : "an angle has no scale") + ")");
  return b;
}

const std::vector<std::string>& cacheBlocks() {
  static const std::vector<std::string> blocks = [] {
    std::vector<std::string> b;
    for (Feature f : kKeypointBlocks) b.push_back(featureName(f));
    for (Feature f : kShapeBlocks) b.push_back(featureName(f));
    for (Feature f : kKeypointBlocks) b.push_back(kRandom + featureName(f));
    for (const auto* fs : {&kKeypointBlocks, &kShapeBlocks})
      for (Feature f : *fs)
        if (!isAngleFeature(f)) b.push_back(kScaled + featureName(f));
    b.push_back(kSize);
    b.push_back(kKeypointSet);
    for (const char* p : {"esf", "vfh", "ourcvfh"}) b.push_back(p);
    return b;
  }();
  return blocks;
}

FeatureTable featureLayout(const std::vector<std::string>& blocks, const DescriptorOptions& options) {
  FeatureTable t;
  for (const auto& b : blocks) {
    const BlockName name = parseBlockName(b);
    t.blocks.push_back(b);
    t.sizes.push_back(name.kind == BlockName::Peer   ? kPeerSizes.at(b)
                      : name.kind == BlockName::Size ? kSizeBlockWidth
                      : name.kind == BlockName::KeypointSet ? kKeypointSetWidth
                                                     : options.histogram.bins);
  }
  t.spec = featureSpec(options);
  return t;
}

std::string featureCachePath(const std::string& root, const DescriptorOptions& options, int shard, int shards) {
  return dataset::featureCacheFile(root, specHash(options), shard, shards);
}

std::vector<FeatureRow> describeViews(const std::vector<LabelledView>& views, const DescriptorOptions& options,
                                      const FeatureTable& layout, int jobs, DescribeProgress* progress) {
  std::vector<std::size_t> all(views.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return describeSome(views, all, options, layout, jobs, progress);
}

std::string describeCacheShard(const FeatureCache& c, int shard, int shards) {
  if (shards < 1 || shard < 0 || shard >= shards)
    throw Error("shard " + std::to_string(shard + 1) + " of " + std::to_string(shards) +
                ": expected 1 <= shard <= shards");
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < c.views.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(shards)) == shard) mine.push_back(i);
  FeatureTable t = featureLayout(cacheBlocks(), c.options);
  t.rows = describeSome(c.views, mine, c.options, t, c.jobs, c.progress);
  const std::string path = featureCachePath(c.dataset, c.options, shard, shards);
  save(path, t);
  return path;
}

namespace {

// A cache written before a block was added (the same parameters, fewer blocks): its rows keep what
// they hold and only the new blocks are described, instead of every block of every view again.
FeatureTable withNewBlocks(const FeatureCache& c, FeatureTable old, const FeatureTable& layout) {
  std::vector<std::string> added;
  for (const auto& b : layout.blocks)
    if (std::find(old.blocks.begin(), old.blocks.end(), b) == old.blocks.end()) added.push_back(b);
  const FeatureTable sub = featureLayout(added, c.options);
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < c.views.size(); ++i) index[c.views[i].id] = i;
  std::vector<std::size_t> which;
  std::vector<std::size_t> rows_of;
  for (std::size_t r = 0; r < old.rows.size(); ++r)
    if (const auto it = index.find(old.rows[r].id); it != index.end()) which.push_back(it->second), rows_of.push_back(r);
  std::string names;
  for (const auto& b : added) names += (names.empty() ? "" : ", ") + b;
  if (c.progress) c.progress->note("adding " + names + " to the feature cache of " + std::to_string(which.size()) + " views");
  if (c.progress) c.progress->begin(which.size());
  const std::vector<FeatureRow> described = describeRows(c.views, which, c.options, sub, c.jobs, c.progress);
  if (c.progress) c.progress->end();
  FeatureTable t = layout;
  for (std::size_t k = 0; k < which.size(); ++k) {
    FeatureRow row = std::move(old.rows[rows_of[k]]);
    std::vector<float> values(static_cast<std::size_t>(layout.width()), std::nanf(""));
    for (std::size_t b = 0; b < layout.blocks.size(); ++b) {
      const std::string& name = layout.blocks[b];
      const bool is_new = sub.offset(name) >= 0;
      const std::vector<float>& from = is_new ? described[k].values : row.values;
      const int at = is_new ? sub.offset(name) : old.offset(name);
      std::copy_n(from.begin() + at, layout.sizes[b], values.begin() + layout.offset(name));
    }
    row.values = std::move(values);
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

FeatureTable loadOrDescribeCache(const FeatureCache& c) {
  const std::string path = featureCachePath(c.dataset, c.options);
  const FeatureTable layout = featureLayout(cacheBlocks(), c.options);
  FeatureTable t = layout;
  std::error_code ec;
  const bool cached = fs::exists(path, ec);
  if (cached) {
    try {
      t = loadFeatureTable(path);
    } catch (const Error& e) {
      if (c.progress) c.progress->warning(std::string(e.what()) + " — describing the views again");
      t = layout;
    }
  } else {
    mergeShards(c.dataset, specHash(c.options), t, c.progress);
  }
  bool upgraded = false;
  if (t.spec == layout.spec && t.blocks != layout.blocks && hasBlocks(layout, t.blocks) && !t.rows.empty()) {
    std::set<std::string> ids;
    for (const auto& row : t.rows) ids.insert(row.id);
    const bool new_views = std::any_of(c.views.begin(), c.views.end(), [&](const auto& v) { return !ids.count(v.id); });
    if (new_views || !hasBlocks(t, c.needs)) {
      t = withNewBlocks(c, std::move(t), layout);
      upgraded = true;
    }
  } else if (t.blocks != layout.blocks || t.spec != layout.spec) {
    t = layout;
  }
  // Keep cached rows of views still listed; describe the rest.
  std::map<std::string, FeatureRow> have;
  for (auto& row : t.rows) have[row.id] = std::move(row);
  std::vector<std::size_t> missing;
  for (std::size_t i = 0; i < c.views.size(); ++i)
    if (!have.count(c.views[i].id)) missing.push_back(i);
  t.rows.clear();
  if (!missing.empty()) {
    // In batches, saving what is described now and then: an interrupted run loses one batch at most.
    if (c.progress) c.progress->begin(missing.size());
    const std::size_t batch = std::max<std::size_t>(1, c.checkpoint_views);
    auto saved = std::chrono::steady_clock::now();
    for (std::size_t from = 0; from < missing.size(); from += batch) {
      const std::vector<std::size_t> part(missing.begin() + static_cast<std::ptrdiff_t>(from),
                                          missing.begin() + static_cast<std::ptrdiff_t>(std::min(missing.size(), from + batch)));
      for (auto& row : describeRows(c.views, part, c.options, t, c.jobs, c.progress)) have[row.id] = std::move(row);
      const auto now = std::chrono::steady_clock::now();
      if (from + batch < missing.size() && std::chrono::duration<double>(now - saved).count() >= c.checkpoint_s) {
        FeatureTable so_far = t;
        for (const auto& v : c.views)
          if (const auto it = have.find(v.id); it != have.end()) so_far.rows.push_back(it->second);
        save(path, so_far);
        saved = now;
      }
    }
    if (c.progress) c.progress->end();
  }
  for (const auto& v : c.views) t.rows.push_back(std::move(have[v.id]));
  if (!missing.empty() || !cached || upgraded) save(path, t);
  return t;
}

}  // namespace keyturn::learning
