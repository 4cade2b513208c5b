// knn-relative's instance spread (issue 47, the open-set category model): a category of several
// instances is scaled by how far its instances' views lie from each other's, so a view of an instance
// the model never saw is judged by that spread and not by the noise between neighbouring views of one
// instance; single-instance categories take the median ratio. And the folds that test both kinds of
// new object at once (open-set-instance).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_file.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_training.h"
#include "keyturn/learning/open_set_calibration.h"
#include "keyturn/learning/splits.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::learning;
using keyturn::test::errorOf;

namespace {

constexpr int kDims = 9;  // six category axes, three instance axes
constexpr float kNoise = 0.3f;    // a view's noise around its instance's centre, per feature
constexpr float kInstance = 3.f;  // an instance's offset from its category's centre, on the category's own axis

// `per` views of instance `i` of category k: around 8 · e_k + (i - 1) · kInstance · e_(k + 6) (instance 1
// at the category's centre), noise kNoise on every feature.
void addInstance(FeatureTable& t, int k, int i, int per, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.f, 1.f);
  for (int v = 0; v < per; ++v) {
    FeatureRow row;
    row.cls = "c" + std::to_string(k);
    row.instance = row.cls + "_i" + std::to_string(i);
    row.id = row.instance + "/v" + std::to_string(v);
    row.elevation = "30";
    row.keypoints = 40;
    for (int d = 0; d < kDims; ++d)
      row.values.push_back((d == k ? 8.f : 0.f) + (d == k + 6 ? (i - 1) * kInstance : 0.f) + kNoise * noise(rng));
    t.rows.push_back(row);
  }
}

FeatureTable emptyTable() {
  FeatureTable t;
  t.blocks = {"kpd2"};
  t.sizes = {kDims};
  DescriptorOptions o;
  o.histogram.bins = kDims;
  t.spec = featureSpec(o);
  return t;
}

// Categories c0..c2 with instances 0 and 2 (their centres 2 · kInstance apart), c3..c5 with one.
FeatureTable training() {
  FeatureTable t = emptyTable();
  for (int k = 0; k < 6; ++k)
    for (int i : k < 3 ? std::vector<int>{0, 2} : std::vector<int>{1}) addInstance(t, k, i, 40, 100 + 10 * k + i);
  return t;
}

ClassifierParams fastXgboost() {
  ClassifierParams p;
  p.xgboost.rounds = 10;
  p.xgboost.threads = 1;
  return p;
}

Model trainWith(const FeatureTable& t, const std::string& spread) {
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  o.scale_by = "pooled";
  o.false_accept = 0.05;
  o.groups = 3;
  o.class_spread = spread;
  return trainModel(t, {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
}

// The fraction of the table's views answered with their own category.
double namedRight(const Model& m, const FeatureTable& t) {
  double right = 0;
  for (const auto& p : predictRows(m, t, "m")) right += p.answer == Answer::Class && m.info.classes[static_cast<std::size_t>(p.best)] == t.rows[p.row].cls;
  return right / static_cast<double>(t.rows.size());
}

// The fraction answered "unknown".
double unknown(const Model& m, const FeatureTable& t) {
  double n = 0;
  for (const auto& p : predictRows(m, t, "m")) n += p.answer == Answer::Unknown;
  return n / static_cast<double>(t.rows.size());
}

}  // namespace

TEST(OpenSetInstanceSpread, ACategorysScaleIsTheDistanceBetweenItsInstancesAndASingleInstanceOneTakesTheMedianRatio) {
  const FeatureTable t = training();
  Matrix x(static_cast<Eigen::Index>(t.rows.size()), kDims);
  std::vector<int> y;
  std::vector<std::string> instances;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    for (int d = 0; d < kDims; ++d) x(static_cast<Eigen::Index>(r), d) = t.rows[r].values[static_cast<std::size_t>(d)];
    y.push_back(std::stoi(t.rows[r].cls.substr(1)));
    instances.push_back(t.rows[r].instance);
  }
  const OpenSet views = fitOpenSetScorer("knn-relative", x, y, 1, "pooled", nullptr, 1.0, "views", &instances);
  const OpenSet spread = fitOpenSetScorer("knn-relative", x, y, 1, "pooled", nullptr, 1.0, "instances", &instances);
  EXPECT_EQ(spread.class_spread, "instances");
  ASSERT_EQ(spread.class_scale.size(), 6u);
  std::vector<double> ratios;
  for (int c = 0; c < 3; ++c) ratios.push_back(spread.class_scale[c] / views.class_scale[c]);
  // Two instances 6 apart on one of 9 standardised features (the feature's spread over all views is
  // about 1.5): RMS distance ≈ 6 / 1.5 / √12 ≈ 1.1, against neighbouring views' ≈ 0.3 · √2 / ~1 … 0.2;
  // the ratio is well above 2 whatever the noise draw, and the same for the three alike categories.
  for (double r : ratios) {
    EXPECT_GT(r, 2.5) << r;
    EXPECT_NEAR(r, ratios[0], 0.25 * ratios[0]);
  }
  std::sort(ratios.begin(), ratios.end());
  for (int c = 3; c < 6; ++c)  // one instance: its own scale times the median ratio of c0..c2
    EXPECT_NEAR(spread.class_scale[c] / views.class_scale[c], ratios[1], 1e-4 * ratios[1]) << c;
  EXPECT_EQ(errorOf([&] { fitOpenSetScorer("knn-relative", x, y, 1, "pooled", nullptr, 1.0, "instances", nullptr); }),
            "open-set class spread 'instances' needs each training view's instance (360 rows, 0 instances)");
  EXPECT_EQ(errorOf([&] { fitOpenSetScorer("knn-relative", x, y, 1, "pooled", nullptr, 1.0, "models", &instances); }),
            "open-set class spread 'models' is not one of views, instances");
}

TEST(OpenSetInstanceSpread, TheSpreadSurvivesTheModelFileAndABadOneIsNamed) {
  const FeatureTable train = training();
  const Model views = trainWith(train, "views"), spread = trainWith(train, "instances");
  // The instance spread loosens every class's scale (c0..c2 by their own ratio, c3..c5 by the median).
  for (std::size_t c = 0; c < 6; ++c)
    EXPECT_GT(spread.info.open_set.class_scale[c], 2.f * views.info.open_set.class_scale[c]) << c;
  // Kept in the model file, so enroll recalibrates the same way; a bad spread is named.
  const std::filesystem::path dir = keyturn::test::scratchPath("instance_spread_model");
  saveModel(dir.string(), spread);
  const Model back = loadModel(dir.string());
  EXPECT_EQ(back.info.open_set.class_spread, "instances");
  EXPECT_EQ(back.info.open_set.class_scale, spread.info.open_set.class_scale);
  nlohmann::json sidecar = nlohmann::json::parse(keyturn::test::readText(dir / "model.json"));
  EXPECT_EQ(sidecar["open_set"]["class_spread"], "instances");
  sidecar["open_set"]["class_spread"] = "models";
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(errorOf([&] { loadModel(dir.string()); }),
            (dir / "model.json").string() + ": open_set: open-set class spread 'models' is not one of views, instances");
  saveModel(dir.string(), views);
  EXPECT_FALSE(nlohmann::json::parse(keyturn::test::readText(dir / "model.json"))["open_set"].contains("class_spread"));
  std::filesystem::remove_all(dir);
}

TEST(OpenSetInstanceFolds, EachFoldLeavesCategoriesOutAndTestsOneUnseenInstanceOfEveryOtherSeveralInstanceCategory) {
  std::vector<std::string> categories, instances;
  const auto add = [&](const std::string& c, const std::string& i, int views) {
    for (int v = 0; v < views; ++v) categories.push_back(c), instances.push_back(i);
  };
  add("box", "cracker", 3), add("box", "sugar", 3), add("can", "soup", 2), add("can", "chef", 2);
  add("fruit", "apple", 2), add("fruit", "pear", 2), add("fruit", "plum", 2), add("mug", "mug", 2), add("drill", "drill", 2);
  const std::vector<Fold> folds = openSetInstanceFolds(categories, instances, 5, 7);
  ASSERT_EQ(folds.size(), 5u);  // every group leaves at least one several-instance category in
  std::set<std::string> tested;
  for (const Fold& f : folds) {
    std::set<std::string> unknown_categories, test_instances, train_instances, test_categories;
    for (auto r : f.unknown) unknown_categories.insert(categories[r]);
    for (auto r : f.test) test_instances.insert(instances[r]), test_categories.insert(categories[r]);
    for (auto r : f.train) train_instances.insert(instances[r]);
    EXPECT_EQ(f.train.size() + f.test.size() + f.unknown.size(), categories.size()) << f.name;
    EXPECT_EQ(unknown_categories.size(), 1u) << f.name;  // 5 categories, 5 groups
    for (auto r : f.train) EXPECT_FALSE(unknown_categories.count(categories[r])) << f.name;
    // One instance per tested category, never trained on; single-instance categories never tested.
    EXPECT_EQ(test_instances.size(), test_categories.size()) << f.name;
    for (const auto& i : test_instances) EXPECT_FALSE(train_instances.count(i)) << f.name << " " << i;
    EXPECT_FALSE(test_categories.count("mug") || test_categories.count("drill")) << f.name;
    for (const std::string c : {"box", "can", "fruit"})
      EXPECT_EQ(test_categories.count(c), unknown_categories.count(c) ? 0u : 1u) << f.name << " " << c;
    tested.insert(test_instances.begin(), test_instances.end());
  }
  EXPECT_GE(tested.size(), 5u);  // the folds rotate through the instances
  EXPECT_EQ(errorOf([] { openSetInstanceFolds({"a", "b", "c"}, {"a", "b", "c"}, 3, 7); }),
            "open-set instance folds need a category with at least two instances outside a left-out group (none has)");
}
