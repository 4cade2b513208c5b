// The feature cache: CSV round trip, block selection, shard merging and the
// errors a damaged cache produces.
#include "keyturn/learning/feature_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn::learning;
namespace fs = std::filesystem;

namespace {

FeatureTable sample(int first_view, int views) {
  FeatureTable t;
  t.blocks = {"kpd2", "esf"};
  t.sizes = {3, 2};
  t.spec = {{"bins", "3"}, {"keypoints", "iss"}};
  for (int v = first_view; v < first_view + views; ++v) {
    FeatureRow r;
    r.id = "mug/m1/e30/a" + std::to_string(v * 5);
    r.cls = "mug";
    r.instance = "m1";
    r.elevation = "30";
    r.keypoints = 10 + v;
    // 1 + 3 ulp needs 9 significant digits: the cache must give back the same float.
    r.values = {0.25f * v, 0.5f, 1.00000036f, 1e-7f, v == 1 ? std::nanf("") : 3.f};
    if (v == 1) r.problem = "too few keypoints, 2";
    t.rows.push_back(r);
  }
  return t;
}

std::string path(const fs::path& dir, const std::string& name) { return (dir / name).string(); }

}  // namespace

TEST(FeatureTable, RoundTripKeepsLabelsValuesAndMissingValues) {
  const keyturn::test::ScratchFolder scratch("feature_table");
  const FeatureTable t = sample(0, 3);
  saveFeatureTable(path(scratch.made(), "t.csv"), t);
  const FeatureTable r = loadFeatureTable(path(scratch.made(), "t.csv"));
  EXPECT_EQ(r.blocks, t.blocks);
  EXPECT_EQ(r.sizes, t.sizes);
  EXPECT_EQ(r.spec, t.spec);
  ASSERT_EQ(r.rows.size(), 3u);
  EXPECT_EQ(r.rows[2].id, "mug/m1/e30/a10");
  EXPECT_EQ(r.rows[2].keypoints, 12);
  EXPECT_EQ(r.rows[1].problem, "too few keypoints; 2");
  EXPECT_FLOAT_EQ(r.rows[2].values[0], 0.5f);
  EXPECT_FLOAT_EQ(r.rows[0].values[3], 1e-7f);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(r.rows[i].values[k], t.rows[i].values[k]) << i << "," << k;
  EXPECT_TRUE(std::isnan(r.rows[1].values[4]));
}

TEST(FeatureTable, SelectConcatenatesBlocksInTheAskedOrder) {
  const FeatureTable t = sample(0, 3);
  const Matrix m = t.select({"esf", "kpd2"}, {2, 0});
  ASSERT_EQ(m.rows(), 2);
  ASSERT_EQ(m.cols(), 5);
  EXPECT_FLOAT_EQ(m(0, 1), 3.f);   // esf_1 of view 2
  EXPECT_FLOAT_EQ(m(0, 2), 0.5f);  // kpd2_0 of view 2
  EXPECT_FLOAT_EQ(m(1, 2), 0.f);   // kpd2_0 of view 0
  EXPECT_NE(keyturn::test::errorOf([&] { t.select({"vfh"}, {0}); }).find("no 'vfh' block"), std::string::npos);
}

TEST(FeatureTable, ShardsMergeAndMismatchedShardsAreRefused) {
  const FeatureTable merged = mergeFeatureTables({sample(0, 2), sample(2, 3)}, {"s1", "s2"});
  EXPECT_EQ(merged.rows.size(), 5u);
  EXPECT_EQ(merged.rows[4].id, "mug/m1/e30/a20");
  FeatureTable other = sample(2, 1);
  other.spec["bins"] = "64";
  EXPECT_NE(keyturn::test::errorOf([&] { mergeFeatureTables({sample(0, 2), other}, {"s1", "s2"}); })
                .find("s2: computed with other features"),
            std::string::npos);
  EXPECT_NE(keyturn::test::errorOf([&] { mergeFeatureTables({sample(0, 2), sample(1, 2)}, {"s1", "s2"}); })
                .find("also in another shard"),
            std::string::npos);
}

// keyturn train DATASET DATASET…: one camera's views after another's, their ids repeated (the same view
// through each camera), refused where they were described another way.
TEST(FeatureTable, DatasetsTrainedOnTogetherKeepEveryRowAndRefuseOtherFeatures) {
  FeatureTable t = sample(0, 3);
  appendRows(t, sample(0, 2), "openni2");
  ASSERT_EQ(t.rows.size(), 5u);
  EXPECT_EQ(t.rows[3].id, t.rows[0].id) << "the same view through another camera keeps its id";
  FeatureTable other = sample(0, 1);
  other.spec["bins"] = "64";
  EXPECT_EQ(keyturn::test::errorOf([&] { appendRows(t, other, "openni2"); }),
            "openni2: described with other parameters (bins 64, the dataset's 3)");
  other = sample(0, 1);
  other.blocks = {"kpd2", "vfh"};
  EXPECT_EQ(keyturn::test::errorOf([&] { appendRows(t, other, "openni2"); }),
            "openni2: its features have other blocks than the dataset's");
  EXPECT_EQ(t.rows.size(), 5u) << "a refused dataset adds no row";
  EXPECT_EQ(t.blocks, (std::vector<std::string>{"kpd2", "esf"}));
}

// A dataset whose cache was written before a block existed lacks it: the two train on the blocks both
// have, with every value where it was.
TEST(FeatureTable, ADatasetWithAnOlderCacheTrainsOnTheBlocksBothHave) {
  for (const bool older_first : {false, true}) {
    FeatureTable newer = sample(0, 2), older = sample(2, 1);
    older.blocks = {"kpd2"};
    older.sizes = {3};
    for (auto& r : older.rows) r.values.resize(3);
    FeatureTable t = older_first ? older : newer;
    appendRows(t, older_first ? newer : older, "other");
    EXPECT_EQ(t.blocks, std::vector<std::string>{"kpd2"}) << older_first;
    ASSERT_EQ(t.rows.size(), 3u);
    const auto& from_newer = t.rows[older_first ? 1 : 0];
    const auto& from_older = t.rows[older_first ? 0 : 2];
    EXPECT_EQ(from_newer.values, (std::vector<float>{0.f, 0.5f, 1.00000036f})) << older_first;
    EXPECT_EQ(from_older.values, (std::vector<float>{0.5f, 0.5f, 1.00000036f})) << older_first;
    EXPECT_EQ(t.select({"kpd2"}, {0, 1, 2}).rows(), 3);
  }
}

TEST(FeatureTable, DamagedCachesNameTheLine) {
  const keyturn::test::ScratchFolder scratch("feature_table");
  saveFeatureTable(path(scratch.made(), "ok.csv"), sample(0, 2));
  std::ifstream in(path(scratch.made(), "ok.csv"));
  std::string text((std::istreambuf_iterator<char>(in)), {});
  struct Case {
    std::string from, to, expected;
  };
  const Case cases[] = {
      {"# keyturn-features 1", "id,class", "not a keyturn feature cache"},
      {",0.5,", ",0.5x,", "line 5: bad value '0.5x' in column kpd2_1"},
      {"mug,m1,30,11,", "mug,m1,30,eleven,", "line 6: bad keypoint count 'eleven'"},
      {"kpd2_2", "kpd2_7", "line 4: column 'kpd2_7' is out of order"},
  };
  for (const auto& c : cases) {
    std::string broken = text;
    const auto at = broken.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    broken.replace(at, c.from.size(), c.to);
    std::ofstream(path(scratch.made(), "bad.csv")) << broken;
    const std::string msg = keyturn::test::errorOf([&] { loadFeatureTable(path(scratch.made(), "bad.csv")); });
    EXPECT_NE(msg.find(c.expected), std::string::npos) << msg;
  }
  std::ofstream(path(scratch.made(), "short.csv")) << text.substr(0, text.size() - 9);
  EXPECT_NE(keyturn::test::errorOf([&] { loadFeatureTable(path(scratch.made(), "short.csv")); }).find("cells, the header has"),
            std::string::npos);
}
