// knn-relative's camera scale (issue 47): a view's distance over its class's scale times its
// camera's factor, so a camera whose views are noisier than the pool's (the SR4000's few keypoints
// against the OpenNI2's) is not judged by the other camera's spread; the factors survive the model
// file, and a model without them keeps the pooled scale. The class scale power (issue 47): a class
// whose own views lie far apart (the screwdriver's) no longer lends that spread to the unknown views
// it is chosen for.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <filesystem>
#include <random>

#include "keyturn/core/cloud.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_training.h"
#include "keyturn/learning/open_set_calibration.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::learning;
using keyturn::test::errorOf;
namespace fs = std::filesystem;

namespace {

constexpr int kDims = 10;

// `per` views of each category first .. first + categories - 1 through a camera whose noise has
// spread `sd`: category k around 8 · e_k, one row per view, the row's camera set.
void addViews(FeatureTable& t, int first, int categories, int per, float sd, const std::string& camera,
              std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.f, 1.f);
  for (int k = first; k < first + categories; ++k)
    for (int i = 0; i < per; ++i) {
      FeatureRow row;
      row.id = camera + "/c" + std::to_string(k) + "/v" + std::to_string(i);
      row.cls = "c" + std::to_string(k);
      row.instance = row.cls + "_i";
      row.elevation = "30";
      row.keypoints = 40;
      row.camera = camera;
      for (int d = 0; d < kDims; ++d) row.values.push_back((d == k ? 8.f : 0.f) + sd * noise(rng));
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

ClassifierParams fastXgboost() {
  ClassifierParams p;
  p.xgboost.rounds = 10;
  p.xgboost.threads = 1;
  return p;
}

Model trainWith(const FeatureTable& t, const std::string& scale_by) {
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  o.scale_by = scale_by;
  o.false_accept = 0.05;
  return trainModel(t, {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
}

// The fraction of the table's rows of `camera` answered with a class (accepted as known).
double accepted(const Model& m, const FeatureTable& t, const std::string& camera) {
  double n = 0, of = 0;
  for (const auto& p : predictRows(m, t, "m"))
    if (t.rows[p.row].camera == camera) of += 1, n += p.answer == Answer::Class;
  return n / of;
}

// Six categories through a tidy camera "640x480" (spread 1) and a noisy one "176x144" (spread 1.8).
FeatureTable training() {
  FeatureTable t = emptyTable();
  addViews(t, 0, 6, 40, 1.f, "640x480", 1);
  addViews(t, 0, 6, 40, 1.8f, "176x144", 2);
  return t;
}

}  // namespace

// The rows of a table as the scorer takes them: features, class (category index), camera.
struct Rows {
  Matrix x;
  std::vector<int> y;
  std::vector<std::string> camera;
};

Rows rowsOf(const FeatureTable& t) {
  Rows r;
  r.x.resize(static_cast<Eigen::Index>(t.rows.size()), kDims);
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    for (int d = 0; d < kDims; ++d) r.x(static_cast<Eigen::Index>(i), d) = t.rows[i].values[static_cast<std::size_t>(d)];
    r.y.push_back(std::stoi(t.rows[i].cls.substr(1)));
    r.camera.push_back(t.rows[i].camera);
  }
  return r;
}

// The median score of the rows of `camera`, each scored against its own class (probability 1).
double medianScore(const OpenSet& s, const Rows& r, const std::string& camera) {
  Matrix p = Matrix::Zero(r.x.rows(), 6);
  for (std::size_t i = 0; i < r.y.size(); ++i) p(static_cast<Eigen::Index>(i), r.y[i]) = 1.f;
  const std::vector<double> scores = openSetScores(s, r.x, p, &r.camera);
  std::vector<double> v;
  for (std::size_t i = 0; i < scores.size(); ++i)
    if (r.camera[i] == camera) v.push_back(scores[i]);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST(OpenSetCameraScale, TheNoisyCamerasKnownViewsScoreAsTheTidyOnesInsteadOfBelowThem) {
  const Rows train = rowsOf(training());
  const OpenSet pooled = fitOpenSetScorer("knn-relative", train.x, train.y, 1, "pooled", &train.camera);
  const OpenSet camera = fitOpenSetScorer("knn-relative", train.x, train.y, 1, "camera", &train.camera);
  EXPECT_EQ(pooled.scale_by, "pooled");
  EXPECT_TRUE(pooled.camera_scale.empty());
  ASSERT_EQ(camera.camera_scale.size(), 2u);
  // Each camera's distance to its nearest training view over the class's pooled scale: the noisy
  // camera's lie farther (measured 2026-12-05: 1.255 and 0.815, ratio 1.54; the noise is 1.8 ×).
  const float noisy = camera.camera_scale.at("176x144"), tidy = camera.camera_scale.at("640x480");
  EXPECT_GT(noisy, 1.1f);
  EXPECT_LT(tidy, 0.9f);
  EXPECT_GT(noisy / tidy, 1.3f);
  EXPECT_LT(noisy / tidy, 2.0f);
  // New views of the known categories through each camera. The pooled scale scores the noisy
  // camera's well under the tidy one's (one threshold turns them away first); the camera scale
  // scores both alike. Measured 2026-12-05: pooled tidy 0.556, noisy 0.435; camera 0.506 and 0.491.
  FeatureTable views = emptyTable();
  addViews(views, 0, 6, 20, 1.f, "640x480", 11);
  addViews(views, 0, 6, 20, 1.8f, "176x144", 12);
  const Rows known = rowsOf(views);
  const double pt = medianScore(pooled, known, "640x480"), pn = medianScore(pooled, known, "176x144");
  const double ct = medianScore(camera, known, "640x480"), cn = medianScore(camera, known, "176x144");
  EXPECT_LT(pn, pt - 0.08) << "pooled: tidy " << pt << ", noisy " << pn;
  EXPECT_NEAR(cn, ct, 0.04) << "camera: tidy " << ct << ", noisy " << cn;
  // A view of no known camera (an unorganized crop: "") is judged by the pooled scale.
  EXPECT_FLOAT_EQ(camera.cameraFactor(""), 1.f);
  EXPECT_FLOAT_EQ(camera.cameraFactor("320x240"), 1.f);
  const std::vector<std::string> none(known.y.size());
  Matrix p = Matrix::Zero(known.x.rows(), 6);
  for (std::size_t i = 0; i < known.y.size(); ++i) p(static_cast<Eigen::Index>(i), known.y[i]) = 1.f;
  EXPECT_EQ(openSetScores(camera, known.x, p, &none), openSetScores(pooled, known.x, p, &none));
}

TEST(OpenSetCameraScale, TrainCalibratesTheCameraScaleForTheStatedRateOnBothCameras) {
  const Model m = trainWith(training(), "camera");
  ASSERT_EQ(m.info.open_set.camera_scale.size(), 2u);
  // Categories the model never saw, through both cameras: accepted at about the stated 5 % or less
  // (measured 2026-12-05: 0 and 0.05), and the known views named (1 and 0.958).
  FeatureTable unknown = emptyTable();
  addViews(unknown, 6, 3, 40, 1.f, "640x480", 21);
  addViews(unknown, 6, 3, 40, 1.8f, "176x144", 22);
  FeatureTable known = emptyTable();
  addViews(known, 0, 6, 20, 1.f, "640x480", 11);
  addViews(known, 0, 6, 20, 1.8f, "176x144", 12);
  EXPECT_LT(accepted(m, unknown, "640x480"), 0.1);
  EXPECT_LT(accepted(m, unknown, "176x144"), 0.1);
  EXPECT_GT(accepted(m, known, "640x480"), 0.9);
  EXPECT_GT(accepted(m, known, "176x144"), 0.9);
}

TEST(OpenSetCameraScale, TheFactorsSurviveTheModelFileAndAnOldModelKeepsThePooledScale) {
  const FeatureTable train = training();
  const Model m = trainWith(train, "camera");
  const fs::path dir = keyturn::test::scratchPath("camera_scale_model");
  saveModel(dir.string(), m);
  const Model back = loadModel(dir.string());
  EXPECT_EQ(back.info.open_set.scale_by, "camera");
  EXPECT_EQ(back.info.open_set.camera_scale, m.info.open_set.camera_scale);
  const auto before = predictRows(m, train, "m"), after = predictRows(back, train, "m");
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_NEAR(after[i].score, before[i].score, 1e-3);
  // Without scale_by (a model from before): the pooled scale, whatever the view's camera.
  nlohmann::json sidecar = nlohmann::json::parse(keyturn::test::readText(dir / "model.json"));
  ASSERT_TRUE(sidecar["open_set"].contains("camera_scale"));
  sidecar["open_set"].erase("scale_by");
  sidecar["open_set"].erase("camera_scale");
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  const Model old = loadModel(dir.string());
  EXPECT_EQ(old.info.open_set.scale_by, "pooled");
  const Model pooled = trainWith(train, "pooled");
  const auto old_scores = predictRows(old, train, "m"), pooled_scores = predictRows(pooled, train, "m");
  for (std::size_t i = 0; i < old_scores.size(); ++i) EXPECT_NEAR(old_scores[i].score, pooled_scores[i].score, 1e-3);
  // A bad scale is named.
  sidecar["open_set"]["scale_by"] = "keypoints";
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(errorOf([&] { loadModel(dir.string()); }),
            (dir / "model.json").string() + ": open_set: open-set scale 'keypoints' is not one of pooled, camera");
  sidecar["open_set"]["scale_by"] = "camera";
  sidecar["open_set"]["camera_scale"] = {{"176x144", -1.0}};
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(errorOf([&] { loadModel(dir.string()); }),
            (dir / "model.json").string() + ": open_set: camera_scale of '176x144' must be positive");
  fs::remove_all(dir);
}

TEST(OpenSetCameraScale, CameraOfTellsAnOrganizedGridFromACrop) {
  Cloud organized;
  organized.width = 176, organized.height = 144;
  organized.points.assign(176 * 144, Eigen::Vector3f(0, 0, 1));
  EXPECT_EQ(cameraOf(organized), "176x144");
  Cloud crop;
  crop.width = 500;
  crop.points.assign(500, Eigen::Vector3f(0, 0, 1));
  EXPECT_EQ(cameraOf(crop), "");
}

namespace {

// Five tidy categories (spread 1) and a spread-out one, category 5 (spread 3), through one camera.
FeatureTable spreadTraining() {
  FeatureTable t = emptyTable();
  addViews(t, 0, 5, 40, 1.f, "640x480", 31);
  addViews(t, 5, 1, 40, 3.f, "640x480", 32);
  return t;
}

// Views of an object the model never saw that lies beside the spread-out category: 8 · e_5 + 5 · e_6.
FeatureTable besideTheSpreadClass(int per, std::uint64_t seed) {
  FeatureTable t = emptyTable();
  addViews(t, 6, 1, per, 1.f, "640x480", seed);
  for (auto& row : t.rows) row.values[5] += 8.f, row.values[6] -= 3.f, row.cls = "beside", row.instance = "beside_i";
  return t;
}

Model trainWithPower(const FeatureTable& t, double power) {
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  o.false_accept = 0.05;
  o.class_scale_power = power;
  return trainModel(t, {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
}

}  // namespace

TEST(OpenSetClassScale, ThePowerDrawsEachClassScaleTowardTheMedianClasss) {
  const Rows r = rowsOf(spreadTraining());
  const OpenSet own = fitOpenSetScorer("knn-relative", r.x, r.y, 1, "pooled", nullptr, 1.0);
  const OpenSet one = fitOpenSetScorer("knn-relative", r.x, r.y, 1, "pooled", nullptr, 0.0);
  const OpenSet half = fitOpenSetScorer("knn-relative", r.x, r.y, 1, "pooled", nullptr, 0.5);
  ASSERT_EQ(own.class_scale.size(), 6u);
  std::vector<float> sorted = own.class_scale;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[3];  // upperMedian (core/median.h): the upper middle of an even count
  // The spread-out class's own scale is about 3 × the tidy ones' (its noise is).
  EXPECT_GT(own.class_scale[5], 2.f * sorted[2]);
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_NEAR(one.class_scale[c], median, 1e-4 * median);
    EXPECT_NEAR(half.class_scale[c], std::sqrt(own.class_scale[c] * median), 1e-4 * median);
  }
  EXPECT_EQ(half.class_scale_power, 0.5);
  EXPECT_EQ(errorOf([&] { fitOpenSetScorer("knn-relative", r.x, r.y, 1, "pooled", nullptr, 1.5); }),
            "open-set class scale power must be within [0, 1], not 1.500000");
}

TEST(OpenSetClassScale, AnUnknownObjectBesideASpreadOutClassIsTurnedAwayMoreOftenAndMoreKnownViewsAreNamed) {
  const FeatureTable train = spreadTraining();
  const Model own = trainWithPower(train, 1.0), drawn = trainWithPower(train, 0.5);
  const FeatureTable beside = besideTheSpreadClass(60, 41);
  FeatureTable known = emptyTable();
  addViews(known, 0, 5, 20, 1.f, "640x480", 42);
  addViews(known, 5, 1, 20, 3.f, "640x480", 43);
  const double own_beside = accepted(own, beside, "640x480"), drawn_beside = accepted(drawn, beside, "640x480");
  const double own_known = accepted(own, known, "640x480"), drawn_known = accepted(drawn, known, "640x480");
  std::cout << "beside the spread class accepted: power 1 " << own_beside << ", power 0.5 " << drawn_beside
            << "; known named: " << own_known << ", " << drawn_known << "\n";
  // At the same stated rate, drawing the scales toward the median turns more of the object beside the
  // spread-out class away and names more of the known views (measured 2026-12-06: beside 0.80 -> 0.68,
  // known 0.33 -> 0.80; the spread-out class's loose scale made the calibration strict for every class).
  EXPECT_LT(drawn_beside, own_beside - 0.05);
  EXPECT_GT(drawn_known, own_known + 0.25);
}

TEST(OpenSetClassScale, ThePowerSurvivesTheModelFileAndABadOneIsNamed) {
  const Model m = trainWithPower(spreadTraining(), 0.5);
  const fs::path dir = keyturn::test::scratchPath("class_scale_power_model");
  saveModel(dir.string(), m);
  const Model back = loadModel(dir.string());
  EXPECT_EQ(back.info.open_set.class_scale_power, 0.5);
  EXPECT_EQ(back.info.open_set.class_scale, m.info.open_set.class_scale);
  nlohmann::json sidecar = nlohmann::json::parse(keyturn::test::readText(dir / "model.json"));
  sidecar["open_set"].erase("class_scale_power");  // a model from before: each class's own scale
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(loadModel(dir.string()).info.open_set.class_scale_power, 1.0);
  sidecar["open_set"]["class_scale_power"] = -0.5;
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(errorOf([&] { loadModel(dir.string()); }),
            (dir / "model.json").string() + ": open_set: class_scale_power must be within [0, 1]");
  fs::remove_all(dir);
}
