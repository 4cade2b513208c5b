// Each protocol's split logic: folds partition the rows, and no instance or
// elevation leaks from a test fold into its training set.
#include "keyturn/learning/splits.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/protocols.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "support/error_of.h"

using namespace keyturn::learning;

namespace {

// 3 categories; "bottle" and "can" have two instances; 3 elevations × 8 views each.
struct Views {
  std::vector<std::string> category, instance, elevation, id;
};

Views makeViews() {
  Views v;
  const std::vector<std::pair<std::string, std::string>> objects = {
      {"bottle", "b1"}, {"bottle", "b2"}, {"can", "c1"}, {"can", "c2"}, {"mug", "m1"}};
  for (const auto& [c, i] : objects)
    for (const char* e : {"30", "45", "60"})
      for (int a = 0; a < 8; ++a) {
        v.category.push_back(c);
        v.instance.push_back(i);
        v.elevation.push_back(e);
        v.id.push_back(c + "/" + i + "/e" + e + "/a" + std::to_string(a * 45));
      }
  return v;
}

std::set<std::string> valuesAt(const std::vector<std::string>& col, const std::vector<std::size_t>& rows) {
  std::set<std::string> s;
  for (auto r : rows) s.insert(col[r]);
  return s;
}

}  // namespace

TEST(Splits, KFoldPartitionsEveryRowIntoExactlyOneTestFold) {
  const auto folds = kFold(103, 10, 7);
  ASSERT_EQ(folds.size(), 10u);
  std::vector<int> tested(103, 0);
  for (const auto& f : folds) {
    EXPECT_EQ(f.train.size() + f.test.size(), 103u);
    EXPECT_TRUE(f.test.size() == 10u || f.test.size() == 11u) << f.test.size();
    for (auto r : f.test) ++tested[r];
    std::vector<std::size_t> both;
    std::set_intersection(f.train.begin(), f.train.end(), f.test.begin(), f.test.end(), std::back_inserter(both));
    EXPECT_TRUE(both.empty());
  }
  EXPECT_TRUE(std::all_of(tested.begin(), tested.end(), [](int n) { return n == 1; }));
}

TEST(Splits, KFoldShufflesRepeatablyBySeed) {
  EXPECT_EQ(kFold(50, 5, 7)[0].test, kFold(50, 5, 7)[0].test);
  EXPECT_NE(kFold(50, 5, 7)[0].test, kFold(50, 5, 8)[0].test);
  // Shuffled: the first fold is not simply the first ten rows.
  EXPECT_NE(kFold(50, 5, 7)[0].test, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(Splits, LeaveOneElevationOutNeverTrainsOnTheTestElevation) {
  const Views v = makeViews();
  const auto folds = leaveOneGroupOut(v.elevation, "elevation");
  ASSERT_EQ(folds.size(), 3u);
  for (const auto& f : folds) {
    const auto test = valuesAt(v.elevation, f.test);
    const auto train = valuesAt(v.elevation, f.train);
    ASSERT_EQ(test.size(), 1u);
    EXPECT_EQ(train.count(*test.begin()), 0u) << f.name;
    EXPECT_EQ(train.size(), 2u);
    EXPECT_EQ(f.test.size(), 40u);
  }
}

TEST(Splits, LeaveOneInstanceOutTestsOnlyUnseenInstancesOfSharedCategories) {
  const Views v = makeViews();
  const auto folds = leaveOneInstanceOut(v.category, v.instance);
  ASSERT_EQ(folds.size(), 4u);  // b1, b2, c1, c2 — "mug" has one instance and no fold
  for (const auto& f : folds) {
    const auto test = valuesAt(v.instance, f.test);
    ASSERT_EQ(test.size(), 1u);
    EXPECT_EQ(valuesAt(v.instance, f.train).count(*test.begin()), 0u) << f.name;
    // The category itself is still trained on (through its other instance).
    EXPECT_EQ(valuesAt(v.category, f.train).count(v.category[f.test[0]]), 1u) << f.name;
    EXPECT_EQ(f.test.size(), 24u);
    EXPECT_EQ(f.train.size(), 96u);
  }
}

// Nested validation inside leave-instance's fold for b1: the other folds (b2, c1, c2) tested against
// the rest of b1's training views; b1's views are in none of them, and each inner fold partitions
// the outer fold's training views.
TEST(Splits, InnerFoldsNeverHoldTheOuterTestViews) {
  const Views v = makeViews();
  const auto outer = leaveOneInstanceOut(v.category, v.instance);
  ASSERT_EQ(outer.size(), 4u);
  const auto inner = innerFolds(outer, 0, 3);
  ASSERT_EQ(inner.size(), 3u);
  for (const auto& f : inner) {
    EXPECT_EQ(f.test.size() + f.train.size(), outer[0].train.size());
    EXPECT_EQ(valuesAt(v.instance, f.test).size(), 1u);
    EXPECT_EQ(valuesAt(v.instance, f.train).count(*valuesAt(v.instance, f.test).begin()), 0u);
    for (auto r : outer[0].test) {
      EXPECT_FALSE(std::binary_search(f.test.begin(), f.test.end(), r));
      EXPECT_FALSE(std::binary_search(f.train.begin(), f.train.end(), r));
    }
  }
  EXPECT_EQ(innerFolds(outer, 0, 2).size(), 2u) << "at most max_inner";
  // Spread evenly: k-fold 10's fold 4 validates on folds 1, 5 and 8 of the other nine.
  const auto k10 = innerFolds(kFold(100, 10, 7), 3, 3);
  ASSERT_EQ(k10.size(), 3u);
  EXPECT_EQ(k10[0].name, "fold 1");
  EXPECT_EQ(k10[1].name, "fold 5");
  EXPECT_EQ(k10[2].name, "fold 8");
  EXPECT_TRUE(innerFolds({fixedSplit(v.id, {v.id[0]})}, 0, 3).empty()) << "one fold leaves nothing to choose on";
}

TEST(Splits, FixedSplitByViewIds) {
  const Views v = makeViews();
  const Fold f = fixedSplit(v.id, {"mug/m1/e30/a0", "can/c2/e60/a315"});
  EXPECT_EQ(f.test, (std::vector<std::size_t>{95, 96}));
  EXPECT_EQ(f.train.size(), v.id.size() - 2);
  const std::string msg = keyturn::test::errorOf([&] { fixedSplit(v.id, {"mug/m9/e30/a0"}); });
  EXPECT_NE(msg.find("'mug/m9/e30/a0' is not in the dataset"), std::string::npos) << msg;
}

TEST(Splits, DegenerateInputsAreClearErrors) {
  EXPECT_NE(keyturn::test::errorOf([] { kFold(3, 10, 7); }).find("at least k rows"), std::string::npos);
  EXPECT_NE(keyturn::test::errorOf([] { leaveOneGroupOut({"30", "30"}, "elevation"); }).find("two elevations"),
            std::string::npos);
  EXPECT_NE(keyturn::test::errorOf([] { leaveOneInstanceOut({"a", "b"}, {"a1", "b1"}); }).find("two instances"),
            std::string::npos);
}

// Instances numbered per class (SR4K-D style "1", "2") stay different objects; names unique
// across classes keep their own text (the built-in model's class names).
TEST(Labels, AnInstanceIsItsClassAndInstance) {
  keyturn::learning::FeatureTable t;
  for (const auto& [c, i] : std::vector<std::pair<std::string, std::string>>{
           {"mug", "1"}, {"bowl", "1"}, {"bowl", "2"}, {"can", "ycb_005"}, {"mug", "1"}}) {
    keyturn::learning::FeatureRow r;
    r.cls = c;
    r.instance = i;
    t.rows.push_back(r);
  }
  const Labels l = labelRows(t, LabelKind::Instance);
  EXPECT_EQ(l.names, (std::vector<std::string>{"2", "bowl/1", "mug/1", "ycb_005"}));
  EXPECT_EQ(l.of_row, (std::vector<int>{2, 1, 0, 3, 2}));
  EXPECT_EQ(labelRows(t, LabelKind::Category).names, (std::vector<std::string>{"bowl", "can", "mug"}));
}
