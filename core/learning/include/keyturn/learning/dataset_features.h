#pragma once
// A dataset's features: its views (dataset::datasetViews) described through its feature cache. The
// one path from a dataset to its feature table, taken by the command line (evaluate, train,
// consistency) and by Python's Dataset.features.
#include <string>
#include <vector>

#include "keyturn/learning/feature_cache.h"

namespace keyturn::learning {

enum class CacheWrite {
  Fill,   // loadOrDescribeCache: the cache read, the views it lacks described, the cache written
  Never,  // the cache's rows when it holds every view; else the views described in memory, nothing written
};

struct DatasetFeatures {
  FeatureTable table;  // Fill: every cache block; Never: every cache block when read, else `blocks`
  std::string cache;   // the cache file read or written; "" when described in memory
};

// `blocks`: the blocks the caller reads. Never: the blocks to describe in memory when the cache cannot
// answer (a block named twice is described once); every cache block when empty. Fill: an older cache
// gains those of them it lacks (FeatureCache::needs). Throws keyturn::Error for an unknown block.
DatasetFeatures datasetFeatures(const FeatureCache& cache, CacheWrite write, const std::vector<std::string>& blocks = {});

}  // namespace keyturn::learning
