#pragma once
// Where a dataset keeps its feature cache (docs/results.md): keyturn's own folder DATASET/.keyturn/,
// which holds no views (verify does not call its files orphans), with one features-<hash>.csv per
// feature specification and the shard files an array job writes beside it. What the files hold is
// learning's (keyturn/learning/feature_cache.h); where they are is the dataset's.
#include <map>
#include <string>
#include <vector>

#include "keyturn/dataset/dataset_layout.h"  // kKeyturnFolder

namespace keyturn::dataset {

// DATASET/.keyturn/features-<hash>[.shard-I-of-N].csv; shard counts from 0, I = shard + 1.
std::string featureCacheFile(const std::string& root, const std::string& hash, int shard = 0, int shards = 1);

// The shard files of the cache with this hash that are there, by shard count N, each list sorted by
// name; a count with fewer than N files is an incomplete set.
std::map<int, std::vector<std::string>> featureCacheShards(const std::string& root, const std::string& hash);

}  // namespace keyturn::dataset
