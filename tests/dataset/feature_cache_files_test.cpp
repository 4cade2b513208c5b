// Where a dataset keeps its feature cache: DATASET/.keyturn/features-HASH[.shard-I-of-N].csv, and the
// shard files found there grouped by their count.
#include "keyturn/dataset/feature_cache_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/scratch_path.h"

using namespace keyturn;
namespace fs = std::filesystem;

TEST(FeatureCacheFiles, TheCacheAndItsShardsAreNamedInTheDatasetsKeyturnFolder) {
  EXPECT_EQ(dataset::featureCacheFile("/data/ds", "0123456789abcdef"), "/data/ds/.keyturn/features-0123456789abcdef.csv");
  EXPECT_EQ(dataset::featureCacheFile("/data/ds", "0123456789abcdef", 2, 16),
            "/data/ds/.keyturn/features-0123456789abcdef.shard-3-of-16.csv");
}

TEST(FeatureCacheFiles, ShardsAreGroupedByTheirCountAndOtherCachesIgnored) {
  const keyturn::test::ScratchFolder scratch("feature_cache_files");
  const std::filesystem::path& d = scratch.path;
  EXPECT_TRUE(dataset::featureCacheShards(d.string(), "aaaa").empty());  // no folder: no shards
  fs::create_directories(d / ".keyturn");
  for (const char* f : {"features-aaaa.shard-2-of-2.csv", "features-aaaa.shard-1-of-2.csv", "features-aaaa.shard-1-of-3.csv",
                        "features-bbbb.shard-1-of-2.csv", "features-aaaa.csv", "features-aaaa.shard-x-of-2.csv"})
    std::ofstream(d / ".keyturn" / f) << "\n";
  const auto sets = dataset::featureCacheShards(d.string(), "aaaa");
  ASSERT_EQ(sets.size(), 2u);
  const std::string k = (d / ".keyturn").string() + "/";
  EXPECT_EQ(sets.at(2), (std::vector<std::string>{k + "features-aaaa.shard-1-of-2.csv", k + "features-aaaa.shard-2-of-2.csv"}));
  EXPECT_EQ(sets.at(3), (std::vector<std::string>{k + "features-aaaa.shard-1-of-3.csv"}));
}
