#include "keyturn/learning/dataset_features.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>

#include "keyturn/core/error.h"

namespace keyturn::learning {
namespace {

// The table's rows for exactly these views, in their order; none when the table lacks one.
std::optional<std::vector<FeatureRow>> rowsOf(const FeatureTable& t, const std::vector<LabelledView>& views) {
  std::map<std::string, const FeatureRow*> by_id;
  for (const auto& r : t.rows) by_id[r.id] = &r;
  std::vector<FeatureRow> rows;
  for (const auto& v : views) {
    const auto it = by_id.find(v.id);
    if (it == by_id.end()) return std::nullopt;
    rows.push_back(*it->second);
  }
  return rows;
}

// The cache file's table restricted to the views, when it was made with these options and holds them
// all and the blocks (every cache block when none are named; an older cache may lack others).
std::optional<FeatureTable> completeCache(const std::string& path, const FeatureCache& c,
                                          const std::vector<std::string>& blocks) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  const FeatureTable layout = featureLayout(cacheBlocks(), c.options);
  try {
    FeatureTable t = loadFeatureTable(path);
    if (t.spec != layout.spec || !hasBlocks(t, blocks.empty() ? cacheBlocks() : blocks)) return std::nullopt;
    auto rows = rowsOf(t, c.views);
    if (!rows) return std::nullopt;
    t.rows = std::move(*rows);
    return t;
  } catch (const Error&) {
    return std::nullopt;  // an unreadable cache is described again, as evaluate does; it is left as it is
  }
}

}  // namespace

DatasetFeatures datasetFeatures(const FeatureCache& c, CacheWrite write, const std::vector<std::string>& blocks) {
  const std::string path = featureCachePath(c.dataset, c.options);
  if (write == CacheWrite::Fill) {
    FeatureCache reading = c;
    reading.needs.insert(reading.needs.end(), blocks.begin(), blocks.end());
    return {loadOrDescribeCache(reading), path};
  }
  if (auto t = completeCache(path, c, blocks)) return {std::move(*t), path};
  std::vector<std::string> unique;
  for (const auto& b : blocks.empty() ? cacheBlocks() : blocks)
    if (std::find(unique.begin(), unique.end(), b) == unique.end()) unique.push_back(b);
  DatasetFeatures out;
  out.table = featureLayout(unique, c.options);
  out.table.rows = describeViews(c.views, c.options, out.table, c.jobs, c.progress);
  return out;
}

}  // namespace keyturn::learning
