// The open-set distance (issue 47): knn's distance to the nearest training views measured as the RMS
// of standardised features (rms) or between the PDFs as described (l1, chi2). Standardising weighs a
// PDF bin by its spread over the training views, so a tail bin that is almost always empty turns a
// little noise there into a large distance; l1 and chi2 weigh the mass that moves.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <random>

#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_file.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_recalibration.h"
#include "keyturn/learning/model_training.h"
#include "keyturn/learning/open_set_calibration.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::learning;
using keyturn::test::errorOf;

namespace {

// Eight-bin PDFs of class `c` (0..5): its mass in bins c and c + 1 (in shares that vary by ±0.05);
// bin 7, past every class's mass (a distance longer than any object's), holds only a trace (1e-4) on
// a few views, as a far pair of noisy keypoints leaves one.
std::vector<float> pdfOf(int c, std::mt19937_64& rng, bool trace) {
  std::uniform_real_distribution<float> share(0.45f, 0.55f);
  std::vector<float> p(8, 0.f);
  const float a = share(rng);
  p[static_cast<std::size_t>(c)] = a;
  p[static_cast<std::size_t>(c + 1)] = 1.f - a;
  if (trace) p[7] = 1e-4f, p[static_cast<std::size_t>(c)] -= 1e-4f;
  return p;
}

// `per` views of each of the six classes, a trace in bin 7 on every `trace_every`-th (0: none), as a
// feature table of one kpd2 block of 8 bins: rows c0/0, c0/1, … (class and instance alike), 30°.
FeatureTable pdfTable(std::uint64_t seed, int per, int trace_every) {
  std::mt19937_64 rng(seed);
  FeatureTable t;
  t.blocks = {"kpd2"};
  t.sizes = {8};
  DescriptorOptions d;
  d.histogram.bins = 8;
  t.spec = featureSpec(d);
  for (int c = 0; c < 6; ++c)
    for (int v = 0; v < per; ++v) {
      FeatureRow row;
      row.cls = "c" + std::to_string(c), row.instance = row.cls, row.id = row.cls + "/" + std::to_string(v);
      row.elevation = "30", row.keypoints = 40;
      row.values = pdfOf(c, rng, trace_every > 0 && v % trace_every == 0);
      t.rows.push_back(row);
    }
  return t;
}

// The table's rows as a matrix, and their classes (c0 → 0, …).
Matrix rowsOf(const FeatureTable& t, std::vector<int>& y) {
  Matrix x(static_cast<Eigen::Index>(t.rows.size()), 8);
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    for (int k = 0; k < 8; ++k) x(static_cast<Eigen::Index>(r), k) = t.rows[r].values[static_cast<std::size_t>(k)];
    y.push_back(std::stoi(t.rows[r].cls.substr(1)));
  }
  return x;
}

Eigen::RowVectorXf standardised(const OpenSet& s, const std::vector<float>& p) {
  Eigen::RowVectorXf v(static_cast<Eigen::Index>(p.size()));
  for (std::size_t k = 0; k < p.size(); ++k) v(static_cast<Eigen::Index>(k)) = (p[k] - s.mean[k]) / s.scale[k];
  return v;
}

}  // namespace

TEST(OpenSetDistance, L1AndChi2MeasureThePdfsAsDescribed) {
  std::vector<int> y;
  const Matrix x = rowsOf(pdfTable(3, 30, 10), y);
  // Worked by hand: [.5 .5 0 0 …] against [.25 .25 .5 0 …]: L1 = .25 + .25 + .5 = 1;
  // χ² = ½ (.25²/.75 + .25²/.75 + .5²/.5) = 1/3.
  const std::vector<float> a = {0.5f, 0.5f, 0, 0, 0, 0, 0, 0}, b = {0.25f, 0.25f, 0.5f, 0, 0, 0, 0, 0};
  for (const auto& [name, expected] : {std::pair<std::string, double>{"l1", 1.0}, {"chi2", 1.0 / 3}}) {
    const OpenSet s = fitOpenSetScorer("knn", x, y, 1, "pooled", nullptr, 1, "views", nullptr, name);
    EXPECT_EQ(s.distance, name);
    EXPECT_NEAR(openSetDistance(s, standardised(s, a), standardised(s, b)), expected, 1e-5) << name;
  }
  const OpenSet rms = fitOpenSetScorer("knn", x, y);
  EXPECT_EQ(rms.distance, "rms");
  const Eigen::RowVectorXf d = standardised(rms, a) - standardised(rms, b);
  EXPECT_NEAR(openSetDistance(rms, standardised(rms, a), standardised(rms, b)), std::sqrt(d.squaredNorm() / 8.0), 1e-6);
}

// The lever: a view of class 0 with 0.02 of its mass in the tail bin 7, and a view of an object the
// model never saw with class 0's bins split 0.30 / 0.70 instead of about half and half. Standardised,
// bin 7's spread over the training views is that of the rare traces (about 1e-5), so the known view's
// 0.02 there counts as thousands of spreads and it lies far beyond the new object (rms); as described,
// it moved 0.04 of its mass and the new object 0.3 (l1, chi2).
TEST(OpenSetDistance, AKnownViewWithATraceInAnEmptyBinStaysNearerThanANewObjectUnderL1) {
  std::vector<int> y;
  const Matrix x = rowsOf(pdfTable(5, 30, 10), y);
  const std::vector<float> known = {0.49f, 0.49f, 0, 0, 0, 0, 0, 0.02f};
  const std::vector<float> unseen = {0.30f, 0.70f, 0, 0, 0, 0, 0, 0};
  Matrix p = Matrix::Zero(2, 6);
  p(0, 0) = p(1, 0) = 1;  // the classifier gives class 0 to both
  Matrix views(2, 8);
  for (int k = 0; k < 8; ++k) views(0, k) = known[static_cast<std::size_t>(k)], views(1, k) = unseen[static_cast<std::size_t>(k)];
  std::map<std::string, std::vector<double>> score;
  for (const char* name : {"rms", "l1", "chi2"})
    score[name] = openSetScores(fitOpenSetScorer("knn-relative", x, y, 1, "pooled", nullptr, 1, "views", nullptr, name), views, p);
  EXPECT_GT(score["l1"][0], score["l1"][1]);
  EXPECT_GT(score["chi2"][0], score["chi2"][1]);
  EXPECT_LT(score["rms"][0], score["rms"][1]);  // standardised, the tail's 0.02 outweighs 0.3 moved
  EXPECT_LT(score["rms"][0], 0.01);
}

TEST(OpenSetDistance, TheDistanceSurvivesTheModelFileAndABadOneIsNamed) {
  const FeatureTable t = pdfTable(7, 20, 0);
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  o.scale_by = "pooled";
  o.groups = 3;
  o.distance = "chi2";
  ClassifierParams params;
  params.xgboost.rounds = 5;
  params.xgboost.threads = 1;
  const Model m = trainModel(t, {"kpd2"}, LabelKind::Instance, params, nullptr, o);
  EXPECT_EQ(m.info.open_set.distance, "chi2");
  const keyturn::test::ScratchFolder folder("open-set-distance");
  const auto& dir = folder.path;
  saveModel(dir.string(), m);
  const Model back = loadModel(dir.string());
  EXPECT_EQ(back.info.open_set.distance, "chi2");
  const auto a = predictRows(m, t, "m"), b = predictRows(back, t, "m");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i].score, b[i].score, 1e-3) << i;  // references kept to 4 decimals

  nlohmann::json sidecar = nlohmann::json::parse(keyturn::test::readText(dir / "model.json"));
  sidecar["open_set"].erase("distance");  // a model from before: rms
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(loadModel(dir.string()).info.open_set.distance, "rms");
  sidecar["open_set"]["distance"] = "cosine";
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(errorOf([&] { loadModel(dir.string()); }),
            (dir / "model.json").string() + ": open_set: open-set distance 'cosine' is not one of rms, l1, chi2");

  // l1 and chi2 compare PDFs: a size block or a peer descriptor is refused, with what to use instead.
  EXPECT_EQ(errorOf([] { checkOpenSetDistanceFor("l1", {"kpd2", "size"}); }),
            "open-set distance 'l1' compares PDFs, and block 'size' is not one: use the rms distance");
  EXPECT_EQ(errorOf([] { checkOpenSetDistanceFor("chi2", {"esf"}); }),
            "open-set distance 'chi2' compares PDFs, and block 'esf' is not one: use the rms distance");
  EXPECT_NO_THROW(checkOpenSetDistanceFor("rms", {"kpd2", "size", "esf"}));
  EXPECT_NO_THROW(checkOpenSetDistanceFor("chi2", {"kpd2", "kpa3", "s_kpd2"}));
}

// keyturn recalibrate: a model's open set calibrated anew from the views it keeps, the classifier
// kept. With the model's own options it comes back as train calibrated it (the kept values are the
// training values to 4 decimals of a spread); with another rate or distance, as asked.
TEST(OpenSetDistance, AModelRecalibratesFromItsKeptViews) {
  const FeatureTable t = pdfTable(11, 24, 6);
  std::vector<double> azimuth;  // each class's 24 views a turn, 15° apart
  for (std::size_t r = 0; r < t.rows.size(); ++r) azimuth.push_back(15.0 * static_cast<double>(r % 24));
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  o.scale_by = "pooled";
  o.groups = 3;
  ClassifierParams params;
  params.xgboost.rounds = 5;
  params.xgboost.threads = 1;
  Model m = trainModel(t, {"kpd2"}, LabelKind::Instance, params, nullptr, o, azimuth);
  const OpenSet trained = m.info.open_set;
  ASSERT_TRUE(std::isfinite(trained.turn_threshold));

  recalibrateOpenSet(m, openSetOptionsOf(m), "m");
  EXPECT_NEAR(m.info.open_set.threshold, trained.threshold, 1e-3);
  EXPECT_NEAR(m.info.open_set.turn_threshold, trained.turn_threshold, 1e-3);
  EXPECT_EQ(m.info.open_set.distance, "rms");

  OpenSetOptions chi2 = openSetOptionsOf(m);
  chi2.distance = "chi2";
  chi2.false_accept = 0.2;
  recalibrateOpenSet(m, chi2, "m");
  EXPECT_EQ(m.info.open_set.distance, "chi2");
  EXPECT_EQ(m.info.open_set.false_accept, 0.2);
  EXPECT_GT(std::abs(m.info.open_set.threshold - trained.threshold), 0.01);
  // Every kept view was left out once, as in train.
  EXPECT_EQ(m.info.open_set.calibration_views, static_cast<int>(t.rows.size()));

  Model closed = trainModel(t, {"kpd2"}, LabelKind::Instance, params);
  EXPECT_NE(errorOf([&] { recalibrateOpenSet(closed, chi2, "closed"); }).find("closed: the model keeps no training views"),
            std::string::npos);
}
