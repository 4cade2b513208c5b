#pragma once
// The feature cache of a dataset (docs/results.md): every view described once
// per parameter set by every block evaluate, train and consistency use —
// ISS keypoint functions, the same on random keypoints (u_*), Osada's
// D2/D3/A3 and the peers ESF, VFH and OUR-CVFH — kept in
// DATASET/.keyturn/features-<hash>.csv. Shards (--shard I/N) are written
// beside it and merged when all are present.
#include <map>
#include <string>

#include "descriptor_options.h"
#include "keyturn/learning/feature_table.h"

namespace keyturn::app {

struct CacheRequest {
  std::string dataset;
  DescriptorFlags flags;
  int jobs = 0;
  bool quiet = false;
  int shard = 0, shards = 1;  // this process describes views i with i % shards == shard
};

// Every parameter that shapes the cached features, as stored in the cache and in models.
std::map<std::string, std::string> featureSpec(const DescriptorFlags& flags);
std::string cachePath(const std::string& dataset, const DescriptorFlags& flags, int shard = 0, int shards = 1);

// Describes the request's views (its shard) and writes the cache or shard file; returns its path.
std::string describeDatasetShard(const CacheRequest& request);
// The whole dataset's features: the cache if it is there, else merged shards
// if all are there, else described now (progress on stderr) and cached.
learning::FeatureTable loadOrDescribeDataset(const CacheRequest& request);

// Describes loose view files (classify): the same blocks, rows without labels.
learning::FeatureTable describeFiles(const std::vector<std::string>& files, const DescriptorFlags& flags, int jobs,
                                     bool quiet, std::vector<std::string>* errors);

}  // namespace keyturn::app
