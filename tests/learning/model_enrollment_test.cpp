// Enrollment (model_enrollment.h): a model keeps what retraining needs (its training views beside
// the open set's references, through the model file), and takes a new object's views: the object
// becomes a class that is named on its own new views while the old classes stay named.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "keyturn/core/error.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_enrollment.h"
#include "keyturn/learning/model_fusion.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_training.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::learning;
using keyturn::test::errorOf;

namespace {

constexpr int kDims = 8;

// `per` views of each object k in `objects` (category "c<k>", instance "i<k>"), unit noise around
// 6 · e_(k mod 6) in the first 6 of 8 dimensions, at two elevations and every 30° of the turntable.
struct Views {
  FeatureTable table;
  std::vector<double> azimuth_deg;
};

Views objectViews(const std::vector<int>& objects, int per, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.f, 1.f);
  Views v;
  v.table.blocks = {"kpd2"};
  v.table.sizes = {kDims};
  DescriptorOptions o;
  o.histogram.bins = kDims;
  v.table.spec = featureSpec(o);
  for (int k : objects)
    for (int i = 0; i < per; ++i) {
      FeatureRow row;
      row.id = "o" + std::to_string(k) + "/" + std::to_string(i);
      row.cls = "c" + std::to_string(k);
      row.instance = "i" + std::to_string(k);
      row.elevation = i % 2 ? "30" : "60";
      row.keypoints = 40;
      for (int d = 0; d < kDims; ++d) row.values.push_back((d == k % kDims ? 6.f : 0.f) + noise(rng));
      // Like a PDF's tail bins: exactly 0 on most views of every object (a value the references give
      // back only to 4 decimals of a spread: the old views must not come back distinguishable by it).
      for (int d = kDims - 2; d < kDims; ++d) row.values[d] = std::max(0.f, noise(rng) - 1.f);
      v.table.rows.push_back(row);
      v.azimuth_deg.push_back(30.0 * (i / 2 % 12));
    }
  return v;
}

ClassifierParams fastXgboost() {
  ClassifierParams p;
  p.xgboost.rounds = 10;
  p.xgboost.threads = 1;
  return p;
}

Model trainedModel(const Views& v) {
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  o.false_accept = 0.1;
  Model m = trainModel(v.table, {"kpd2"}, LabelKind::Instance, fastXgboost(), nullptr, o, v.azimuth_deg);
  addPoseReferences(m, v.table, v.azimuth_deg, LabelKind::Instance, 5);
  return m;
}

// How many of the views are answered with their own instance.
int named(const Model& m, const FeatureTable& t) {
  int n = 0;
  for (const auto& p : predictRows(m, t, "m")) n += answerLabel(m.info, p) == t.rows[p.row].instance;
  return n;
}

}  // namespace

TEST(ModelEnrollment, TheTrainingViewsSurviveTheModelFileAndGiveBackTheRows) {
  Views v = objectViews({0, 1, 2, 3}, 24, 1);
  v.table.rows[5].values[3] = std::nanf("");  // a value the view lacked
  const Model m = trainedModel(v);
  ASSERT_EQ(m.info.training_views.views.size(), v.table.rows.size());
  const keyturn::test::ScratchFolder scratch("model_enrollment_file");
  saveModel(scratch.path.string(), m);
  const Model back = loadModel(scratch.path.string());
  EXPECT_EQ(back.info.training_views.label, LabelKind::Instance);
  EXPECT_EQ(back.info.training_views.open_set_groups, 5);
  const TrainingTable t = modelTrainingTable(back, "m");
  ASSERT_EQ(t.table.rows.size(), v.table.rows.size());
  EXPECT_EQ(t.azimuth_deg, v.azimuth_deg);
  double worst = 0;
  for (std::size_t r = 0; r < v.table.rows.size(); ++r) {
    EXPECT_EQ(t.table.rows[r].cls, v.table.rows[r].cls);
    EXPECT_EQ(t.table.rows[r].instance, v.table.rows[r].instance);
    EXPECT_EQ(t.table.rows[r].elevation, v.table.rows[r].elevation);
    for (int k = 0; k < kDims; ++k) {
      const float a = t.table.rows[r].values[k], b = v.table.rows[r].values[k];
      if (std::isnan(b)) {
        EXPECT_TRUE(std::isnan(a)) << "row " << r << " column " << k;
        continue;
      }
      if (b == 0.f) EXPECT_EQ(a, 0.f) << "row " << r << " column " << k;  // a tail bin's 0 stays 0
      worst = std::max(worst, std::abs(static_cast<double>(a - b)) / back.info.open_set.scale[k]);
    }
  }
  EXPECT_LE(worst, 0.6e-4);  // the references' 4 decimals of a spread
  EXPECT_GT(worst, 0.0);
}

TEST(ModelEnrollment, ANewObjectIsNamedOnItsNewViewsAndTheOldOnesStayNamed) {
  const keyturn::test::ScratchFolder scratch("model_enrollment_new");
  saveModel(scratch.path.string(), trainedModel(objectViews({0, 1, 2, 3}, 24, 1)));
  const Model m = loadModel(scratch.path.string());  // the references as the file keeps them
  const Views object = objectViews({4}, 24, 2);
  const Enrollment e = enrollObject(m, object.table, object.azimuth_deg, "m");
  EXPECT_EQ(e.training_views, 96u);
  EXPECT_EQ(e.new_views, 24u);
  EXPECT_EQ(e.model.info.classes, (std::vector<std::string>{"i0", "i1", "i2", "i3", "i4"}));
  EXPECT_EQ(e.model.info.training_views.views.size(), 120u);
  EXPECT_EQ(e.model.info.open_set.method, "knn-relative");
  EXPECT_DOUBLE_EQ(e.model.info.open_set.false_accept, 0.1);
  EXPECT_EQ(e.model.info.open_set.calibration_views, 120);  // every category left out once, the new one too
  EXPECT_EQ(e.model.info.pose_references.references.rows(), 120);
  EXPECT_EQ(e.model.info.params.xgboost.rounds, 10);
  const Views fresh_object = objectViews({4}, 20, 3), fresh_old = objectViews({0, 1, 2, 3}, 10, 3);
  EXPECT_EQ(named(m, fresh_object.table), 0);  // the old model has no such class
  EXPECT_GE(named(e.model, fresh_object.table), 18);
  EXPECT_GE(named(e.model, fresh_old.table), named(m, fresh_old.table) - 1);
  EXPECT_GE(named(e.model, fresh_old.table), 36);
  // The enrolled model can take another object in turn.
  const Views next = objectViews({5}, 24, 4);
  EXPECT_EQ(enrollObject(e.model, next.table, next.azimuth_deg, "m").model.info.classes.size(), 6u);
}

// A new object indistinguishable from an old one (the same features under another name) takes a
// share of that object's fresh views, not all of them: nothing but the features tells the model's own
// views (given back from the file's references to 4 decimals) from the new object's. When the new
// views kept exact zeros where the old ones came back as ±1e-5, the trees told them apart by that
// and the twin took every fresh view of the old object (the built-in model's objects lost 30 points).
TEST(ModelEnrollment, TheModelsOwnViewsAndTheNewOnesDifferOnlyByTheirFeatures) {
  const keyturn::test::ScratchFolder scratch("model_enrollment_twin");
  saveModel(scratch.path.string(), trainedModel(objectViews({0, 1, 2, 3}, 24, 1)));
  const Model m = loadModel(scratch.path.string());
  Views twin = objectViews({0}, 24, 2);
  for (auto& r : twin.table.rows) r.cls = "c9", r.instance = "i9";
  const Enrollment e = enrollObject(m, twin.table, twin.azimuth_deg, "m");
  const FeatureTable fresh = objectViews({0}, 40, 3).table;
  int old_name = 0, new_name = 0;
  for (const auto& p : predictRows(e.model, fresh, "m")) {
    const std::string& best = e.model.info.classes.at(static_cast<std::size_t>(p.best));
    old_name += best == "i0";
    new_name += best == "i9";
  }
  EXPECT_EQ(old_name + new_name, 40);
  EXPECT_GE(old_name, 8);
  EXPECT_GE(new_name, 8);
}

TEST(ModelEnrollment, RefusesWhatItCannotEnroll) {
  const Model m = trainedModel(objectViews({0, 1, 2, 3}, 24, 1));
  const Views again = objectViews({2}, 8, 2);
  EXPECT_NE(errorOf([&] { enrollObject(m, again.table, again.azimuth_deg, "MODEL"); })
                .find("MODEL: 'i2' is already a class of the model"), std::string::npos);
  const Views two = objectViews({4, 5}, 8, 2);
  EXPECT_EQ(errorOf([&] { enrollObject(m, two.table, two.azimuth_deg, "MODEL"); }),
            "enroll: the new views are of 2 objects, not one");
  Views none = objectViews({4}, 4, 2);
  for (auto& r : none.table.rows) r.keypoints = -1, r.problem = "too few keypoints";
  EXPECT_EQ(errorOf([&] { enrollObject(m, none.table, none.azimuth_deg, "MODEL"); }),
            "enroll: none of the object's 4 views could be described");
  Model old = trainedModel(objectViews({0, 1, 2, 3}, 24, 1));
  old.info.training_views = {};  // a model trained before they were kept
  const Views object = objectViews({4}, 8, 2);
  EXPECT_EQ(errorOf([&] { enrollObject(old, object.table, object.azimuth_deg, "MODEL"); }),
            "MODEL: the model keeps no training views to retrain with (trained before models kept them, or "
            "closed-set): retrain it with keyturn train and a knn or knn-relative open set");
}

TEST(ModelEnrollment, ABadTrainingViewsObjectIsNamed) {
  const Model m = trainedModel(objectViews({0, 1, 2, 3}, 24, 1));
  const keyturn::test::ScratchFolder scratch("model_enrollment_bad");
  saveModel(scratch.path.string(), m);
  const std::string sidecar = (scratch.path / "model.json").string();
  const nlohmann::json good = nlohmann::json::parse(keyturn::test::readText(sidecar));
  const auto load = [&](const nlohmann::json& j) {
    keyturn::test::writeText(sidecar, j.dump());
    return errorOf([&] { loadModel(scratch.path.string()); });
  };
  nlohmann::json j = good;
  j["training_views"]["views"].erase(0);
  EXPECT_EQ(load(j), sidecar + ": training_views: 95 views for 96 open_set references (one each)");
  j = good;
  j["training_views"]["views"][3][0] = 8;
  EXPECT_EQ(load(j), sidecar + ": training_views: view 3 names no capture of the 8 listed");
  j = good;
  j["training_views"]["label"] = "colour";
  EXPECT_EQ(load(j), sidecar + ": training_views: label colour: expected instance or category");
  j = good;
  j["training_views"]["views"][1] = {0, 30.0, {99}};
  EXPECT_EQ(load(j), sidecar + ": training_views: view 1: a missing column outside 0..7");
  // Without the open set's references they describe nothing: the model loads, and cannot be enrolled into.
  j = good;
  j.erase("open_set");
  j.erase("pose_references");
  EXPECT_EQ(load(j), "");
  EXPECT_TRUE(loadModel(scratch.path.string()).info.training_views.empty());
}
