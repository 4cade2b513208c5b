// The dataset feature cache: its name for the default parameters (existing caches
// stay valid), layouts of some blocks computing the same values as the whole cache,
// and the cache reused, refilled and merged from shards.
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/dataset_features.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/tof_view.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::learning;
namespace fs = std::filesystem;

namespace {

class Counting final : public DescribeProgress {
 public:
  void begin(std::size_t views) override { begun += views; }
  void viewDone() override { ++done; }
  void end() override {}
  void note(const std::string& line) override { notes.push_back(line); }
  void warning(const std::string& line) override { notes.push_back(line); }
  std::size_t begun = 0;
  std::atomic<std::size_t> done{0};
  std::vector<std::string> notes;
};

// Three simulated views of the mug in a dataset-like folder.
std::vector<LabelledView> writeViews(const fs::path& root) {
  fs::create_directories(root / "mug");
  const sim::TofViewRenderer renderer(sim::loadMeshOrBuiltin("builtin:mug"));
  std::vector<LabelledView> views;
  for (int i = 0; i < 3; ++i) {
    sim::SceneView v;
    v.turntable_deg = 40.0 * i;
    v.seed = 3 + i;
    const std::string id = "mug/a" + std::to_string(40 * i);
    saveCloud((root / (id + ".pcd")).string(), renderer.render(v));
    views.push_back({id, (root / (id + ".pcd")).string(), "mug", "builtin", "30"});
  }
  return views;
}

std::vector<float> block(const FeatureTable& t, const FeatureRow& r, const std::string& b) {
  const int o = t.offset(b);
  return std::vector<float>(r.values.begin() + o, r.values.begin() + o + t.blockSize(b));
}

// Equal values, a missing one (NaN: a peer that failed on the view, as OUR-CVFH does under ASan)
// equal to a missing one.
::testing::AssertionResult sameValues(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << a.size() << " vs " << b.size() << " values";
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i]))))
      return ::testing::AssertionFailure() << "value " << i << ": " << a[i] << " vs " << b[i];
  return ::testing::AssertionSuccess();
}

}  // namespace

TEST(FeatureCache, SomeBlocksAreTheSameValuesAsTheWholeCache) {
  const keyturn::test::ScratchFolder scratch("feature_cache_blocks");
  const std::filesystem::path& root = scratch.path;
  const auto views = writeViews(root);
  const DescriptorOptions o;
  const FeatureTable all = featureLayout(cacheBlocks(), o);
  const FeatureTable some = featureLayout({"gkpd2", "kpd2", "u_kpa3", "s_gkpd2", "size"}, o);
  const auto full = describeViews(views, o, all, 2, nullptr);
  const auto part = describeViews(views, o, some, 2, nullptr);
  ASSERT_EQ(part.size(), 3u);
  for (std::size_t v = 0; v < views.size(); ++v) {
    ASSERT_EQ(part[v].values.size(), 4u * 32u + 4u);
    EXPECT_GT(part[v].keypoints, 5);
    EXPECT_EQ(part[v].keypoints, full[v].keypoints);
    for (const std::string b : {"gkpd2", "kpd2", "u_kpa3", "s_gkpd2", "size"}) {
      EXPECT_EQ(block(some, part[v], b), block(all, full[v], b)) << views[v].id << " " << b;
      EXPECT_FALSE(std::isnan(block(some, part[v], b).front()));
    }
  }
  EXPECT_FALSE(std::isnan(block(all, full[0], "esf").front())) << "the whole cache holds the peers";
  // The size block is the described view's: the mug (about 12 × 9 × 8 cm) seen from one side.
  const std::vector<float> size = block(all, full[0], "size");
  EXPECT_GT(size[0], 0.02f);
  EXPECT_LT(size[0], 0.08f);
  EXPECT_GE(size[1], size[2]);
  EXPECT_GE(size[2], size[3]);
}

// The cache, train and classify describe a view as `keyturn describe` and the studio's
// recogniser do: the same filtered points, K and PDFs for a full frame with its table.
TEST(FeatureCache, RowsAreWhatDescribeViewGivesForTheSameFrame) {
  const keyturn::test::ScratchFolder scratch("feature_cache_describe");
  const std::filesystem::path& root = scratch.path;
  const auto views = writeViews(root);
  DescriptorOptions o;
  o.features = {Feature::KPD2, Feature::KPA3, Feature::GKPD2};
  const FeatureTable layout = featureLayout({"kpd2", "kpa3", "gkpd2"}, o);
  const auto rows = describeViews(views, o, layout, 1, nullptr);
  ASSERT_EQ(rows.size(), views.size());
  for (std::size_t v = 0; v < views.size(); ++v) {
    const Cloud frame = loadCloud(views[v].path);
    const ViewDescriptor d = describeView(frame, o);
    ASSERT_LT(d.points, frame.validCount() / 2) << "the frame's table is filtered away";
    EXPECT_EQ(rows[v].keypoints, d.keypointCount()) << views[v].id;
    for (std::size_t f = 0; f < o.features.size(); ++f) {
      const auto want = std::vector<float>(d.pdfs[f].begin(), d.pdfs[f].end());
      EXPECT_EQ(block(layout, rows[v], featureName(o.features[f])), want) << views[v].id << " " << f;
    }
  }
}

TEST(FeatureCache, NamedByTheSpecReusedRefilledAndMergedFromShards) {
  // The default parameters of cache version 5 (r_nms 3 since issue 17, smoothed PDFs since issue 30,
  // the filled budget since issue 49, 128 keypoints since issue 47) give this name (a changed default
  // renames the cache); the earlier defaults keep the names their caches had: 64 keypoints filled
  // (2026-12-07) and the capped budget before it.
  EXPECT_EQ(featureCachePath("ds", DescriptorOptions()), "ds/.keyturn/features-d2dabd5565b157be.csv");
  DescriptorOptions filled64;
  filled64.iss.max_keypoints = 64;
  EXPECT_EQ(featureCachePath("ds", filled64), "ds/.keyturn/features-adb63714c4bae4dd.csv");
  DescriptorOptions capped = filled64;
  capped.iss.fill_budget = false;
  EXPECT_EQ(featureCachePath("ds", capped), "ds/.keyturn/features-5663d6ab80b6e754.csv");
  DescriptorOptions other;
  other.histogram.bins = 16;
  EXPECT_NE(featureCachePath("ds", other), featureCachePath("ds", DescriptorOptions()));
  EXPECT_EQ(featureCachePath("ds", DescriptorOptions(), 1, 4), "ds/.keyturn/features-d2dabd5565b157be.shard-2-of-4.csv");
  const FeatureTable all = featureLayout(cacheBlocks(), DescriptorOptions());
  // 6 keypoint + 3 shape + 6 random-keypoint + 7 scaled blocks of 32 bins, size (4), the keypoints
  // (K and 64 × 3 coordinates), ESF, VFH, OUR-CVFH.
  EXPECT_EQ(all.width(), 22 * 32 + 4 + 193 + 640 + 308 + 308);
  EXPECT_THROW(featureLayout({"kpd9"}, DescriptorOptions()), Error);

  const keyturn::test::ScratchFolder scratch("feature_cache_refill");
  const std::filesystem::path& root = scratch.path;
  auto views = writeViews(root);
  DescriptorOptions o;
  o.histogram.bins = 8;
  Counting first;
  const std::vector<LabelledView> two(views.begin(), views.begin() + 2);
  const FeatureTable t2 = loadOrDescribeCache({root.string(), two, o, 2, &first});
  EXPECT_EQ(first.begun, 2u);
  EXPECT_EQ(t2.rows.size(), 2u);
  EXPECT_TRUE(fs::exists(featureCachePath(root.string(), o)));
  Counting second;
  const FeatureTable t3 = loadOrDescribeCache({root.string(), views, o, 2, &second});
  EXPECT_EQ(second.begun, 1u) << "only the new view is described";
  ASSERT_EQ(t3.rows.size(), 3u);
  EXPECT_TRUE(sameValues(t3.rows[0].values, t2.rows[0].values));
  EXPECT_EQ(t3.rows[2].id, views[2].id);

  // Shards of another folder merge into the same table.
  const keyturn::test::ScratchFolder shards_scratch("feature_cache_shards");
  const std::filesystem::path& sharded = shards_scratch.path;
  Counting shards;
  for (int s = 0; s < 2; ++s) describeCacheShard({sharded.string(), views, o, 1, &shards}, s, 2);
  EXPECT_EQ(shards.begun, 3u);
  Counting merge;
  const FeatureTable merged = loadOrDescribeCache({sharded.string(), views, o, 1, &merge});
  EXPECT_EQ(merge.begun, 0u);
  ASSERT_EQ(merge.notes.size(), 1u);
  EXPECT_EQ(merge.notes[0], "merged 2 feature shards");
  ASSERT_EQ(merged.rows.size(), 3u);
  for (std::size_t v = 0; v < 3; ++v) EXPECT_TRUE(sameValues(merged.rows[v].values, t3.rows[v].values)) << v;
  EXPECT_THROW(describeCacheShard({sharded.string(), views, o, 1, nullptr}, 2, 2), Error);
}

// A cache written before a block existed (here: without the keypoints) is read as it is while no
// caller reads the new block; a caller that does gets it described alone, into the cache, with the
// values a fresh describe gives, and the cached rows kept.
TEST(FeatureCache, ABlockAddedLaterIsDescribedAloneIntoTheCache) {
  const keyturn::test::ScratchFolder scratch("feature_cache_new_block");
  const std::filesystem::path& root = scratch.path;
  const auto views = writeViews(root);
  DescriptorOptions o;
  o.histogram.bins = 8;
  const FeatureTable fresh = loadOrDescribeCache({root.string(), views, o, 2, nullptr});
  const std::string path = featureCachePath(root.string(), o);
  // The same cache as an older build wrote it: every block but "kpset"; a marker in one value shows
  // whether the rows were kept or described again.
  std::vector<std::string> older;
  for (const auto& b : cacheBlocks())
    if (b != "kpset") older.push_back(b);
  FeatureTable old = featureLayout(older, o);
  for (const auto& row : fresh.rows) {
    FeatureRow r = row;
    r.values.clear();
    for (const auto& b : older) {
      const std::vector<float> v = block(fresh, row, b);
      r.values.insert(r.values.end(), v.begin(), v.end());
    }
    old.rows.push_back(r);
  }
  old.rows[1].values[static_cast<std::size_t>(old.offset("kpa3"))] = 0.125f;
  saveFeatureTable(path, old);

  Counting as_it_is;
  const FeatureTable older_read = loadOrDescribeCache({root.string(), views, o, 2, &as_it_is});
  EXPECT_EQ(as_it_is.begun, 0u) << "no caller reads kpset: nothing described";
  EXPECT_EQ(older_read.blocks, older);
  EXPECT_EQ(older_read.rows[1].values[static_cast<std::size_t>(older_read.offset("kpa3"))], 0.125f);

  Counting upgrade;
  FeatureCache reading_kpset{root.string(), views, o, 2, &upgrade};
  reading_kpset.needs = {"kpa3", "kpset"};
  const FeatureTable t = loadOrDescribeCache(reading_kpset);
  EXPECT_EQ(upgrade.begun, 3u);
  ASSERT_EQ(upgrade.notes.size(), 1u);
  EXPECT_EQ(upgrade.notes[0], "adding kpset to the feature cache of 3 views");
  ASSERT_EQ(t.blocks, cacheBlocks());
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[1].values[static_cast<std::size_t>(t.offset("kpa3"))], 0.125f) << "the cached rows are kept";
  for (std::size_t v = 0; v < 3; ++v) {
    EXPECT_TRUE(sameValues(block(t, t.rows[v], "kpset"), block(fresh, fresh.rows[v], "kpset"))) << v;
    // K, up to the block's 64 (the default budget is 128: every second keypoint).
    EXPECT_EQ(block(t, t.rows[v], "kpset")[0], static_cast<float>(std::min(fresh.rows[v].keypoints, 64))) << v;
    EXPECT_TRUE(sameValues(block(t, t.rows[v], "esf"), block(fresh, fresh.rows[v], "esf"))) << v;
  }
  Counting again;
  reading_kpset.progress = &again;
  EXPECT_EQ(loadOrDescribeCache(reading_kpset).blocks, cacheBlocks());
  EXPECT_EQ(again.begun, 0u) << "the upgraded cache was written";
}

// A describe stopped part-way (Ctrl-C, a killed job: here the progress throws at the third view) keeps
// the views it had described: the next run describes only the rest, and the table is the one an
// uninterrupted run gives.
TEST(FeatureCache, AnInterruptedDescribeResumesWhereItStopped) {
  class StopAtThird final : public DescribeProgress {
   public:
    void begin(std::size_t) override {}
    void viewDone() override {
      if (++done == 3) throw Error("interrupted");
    }
    void end() override {}
    void note(const std::string&) override {}
    void warning(const std::string&) override {}
    std::atomic<std::size_t> done{0};
  };
  const keyturn::test::ScratchFolder scratch("feature_cache_resume");
  const std::filesystem::path& root = scratch.path;
  const auto views = writeViews(root);
  DescriptorOptions o;
  o.histogram.bins = 8;
  StopAtThird stop;
  FeatureCache c{root.string(), views, o, 1, &stop};
  c.checkpoint_views = 1;  // a save after every view but the last
  c.checkpoint_s = 0;
  EXPECT_THROW(loadOrDescribeCache(c), Error);
  EXPECT_EQ(loadFeatureTable(featureCachePath(root.string(), o)).rows.size(), 2u);
  Counting again;
  c.progress = &again;
  const FeatureTable resumed = loadOrDescribeCache(c);
  EXPECT_EQ(again.begun, 1u) << "only the view the interruption lost is described";
  ASSERT_EQ(resumed.rows.size(), 3u);
  // The same rows as one run through, in the views' order.
  const keyturn::test::ScratchFolder whole_scratch("feature_cache_whole");
  const FeatureTable whole = loadOrDescribeCache({whole_scratch.path.string(), views, o, 1, nullptr});
  for (std::size_t v = 0; v < 3; ++v) {
    EXPECT_EQ(resumed.rows[v].id, views[v].id);
    EXPECT_TRUE(sameValues(resumed.rows[v].values, whole.rows[v].values)) << v;
  }
}

// learning::datasetFeatures, the one path from a dataset to its table (the CLI and Python): Never
// describes in memory the blocks asked for and writes nothing while the cache lacks a view, then
// reads the cache Fill wrote once it holds every view, values equal to those described.
TEST(DatasetFeatures, NeverWritesTheCacheAndReadsItOnceFilled) {
  const keyturn::test::ScratchFolder scratch("dataset_features");
  const std::filesystem::path& root = scratch.path;
  const auto views = writeViews(root);
  const DescriptorOptions o;
  const FeatureCache c{root.string(), views, o, 2, nullptr};
  const std::string path = featureCachePath(root.string(), o);

  const DatasetFeatures memory = datasetFeatures(c, CacheWrite::Never, {"kpd2", "size", "kpd2"});
  EXPECT_EQ(memory.cache, "");
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(root / ".keyturn"));
  EXPECT_EQ(memory.table.blocks, (std::vector<std::string>{"kpd2", "size"}));  // named twice, described once
  ASSERT_EQ(memory.table.rows.size(), 3u);

  // Two threads: every block includes OUR-CVFH, run in the worker program beside the other thread
  // (a fork there deadlocked ASan's allocator until issue 51).
  Counting progress;
  const DatasetFeatures filled = datasetFeatures({root.string(), views, o, 2, &progress}, CacheWrite::Fill);
  EXPECT_EQ(filled.cache, path);
  EXPECT_TRUE(fs::exists(path));
  EXPECT_EQ(progress.done.load(), 3u);
  EXPECT_EQ(filled.table.blocks, cacheBlocks());

  const DatasetFeatures read = datasetFeatures(c, CacheWrite::Never, {"kpd2"});
  EXPECT_EQ(read.cache, path);
  EXPECT_EQ(read.table.blocks, cacheBlocks());  // the cache's table, every block
  ASSERT_EQ(read.table.rows.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(read.table.rows[i].id, views[i].id);
    EXPECT_TRUE(sameValues(block(read.table, read.table.rows[i], "kpd2"), block(memory.table, memory.table.rows[i], "kpd2")));
  }

  // A view the cache lacks: described in memory again, the cache left as it was.
  auto more = views;
  more.push_back(views.front());
  more.back().id = "mug/again";
  const auto before = fs::last_write_time(path);
  const DatasetFeatures partial = datasetFeatures({root.string(), more, o, 2, nullptr}, CacheWrite::Never, {"kpd2"});
  EXPECT_EQ(partial.cache, "");
  EXPECT_EQ(partial.table.rows.size(), 4u);
  EXPECT_EQ(fs::last_write_time(path), before);
}
