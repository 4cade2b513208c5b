// Open-set answers (issue 34): scores, calibration for a stated false-accept rate, the model
// file's open_set, old models staying closed-set, and degenerate views and features.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "keyturn/core/empty_view.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_training.h"
#include "keyturn/learning/open_set_calibration.h"
#include "keyturn/learning/open_set_evaluation.h"
#include "keyturn/learning/protocols.h"
#include "keyturn/learning/recognizer.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::learning;
using keyturn::test::errorOf;
namespace fs = std::filesystem;

namespace {

// Gaussian clusters, one class per category: `per` views of each of `categories` categories
// (numbered from `first`), unit spread around centres `spread` apart on the axes of `dims`
// dimensions (category k at spread · e_k): every category is as far from every other, so a
// category left out is as unlike the rest as any unseen one, and the rate on unseen categories
// measures the calibration rather than which categories happened to be drawn.
struct Clusters {
  Matrix x;
  std::vector<int> y;
  std::vector<std::string> category;
};

// Categories numbered from `noisy_from` on spread `noisy_sd` times as wide (small objects: few keypoints).
Clusters clusters(int categories, int first, int per, int dims, std::uint64_t seed, float spread = 6.f,
                  int noisy_from = 1 << 30, float noisy_sd = 1.f) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.f, 1.f);
  Clusters c;
  c.x.resize(categories * per, dims);
  for (int k = 0; k < categories; ++k)
    for (int i = 0; i < per; ++i) {
      const Eigen::Index r = k * per + i;
      const float sd = first + k >= noisy_from ? noisy_sd : 1.f;
      for (int d = 0; d < dims; ++d) c.x(r, d) = (d == (first + k) % dims ? spread : 0.f) + sd * noise(rng);
      c.y.push_back(k);
      c.category.push_back("c" + std::to_string(first + k));
    }
  return c;
}

ClassifierParams fastXgboost() {
  ClassifierParams p;
  p.xgboost.rounds = 10;
  p.xgboost.threads = 1;
  return p;
}

double acceptedFraction(const OpenSet& s, const std::vector<double>& scores) {
  double n = 0;
  for (double v : scores) n += s.answerFor(v) == Answer::Class;
  return n / static_cast<double>(scores.size());
}

FeatureTable tableOf(const Clusters& c) {
  FeatureTable t;
  t.blocks = {"kpd2"};
  t.sizes = {static_cast<int>(c.x.cols())};
  DescriptorOptions o;
  o.histogram.bins = static_cast<int>(c.x.cols());
  t.spec = featureSpec(o);
  for (Eigen::Index r = 0; r < c.x.rows(); ++r) {
    FeatureRow row;
    row.id = "v" + std::to_string(r);
    row.cls = c.category[static_cast<std::size_t>(r)];
    row.instance = row.cls + "_i";
    row.elevation = r % 2 ? "30" : "60";
    row.keypoints = 40;
    for (Eigen::Index k = 0; k < c.x.cols(); ++k) row.values.push_back(c.x(r, k));
    t.rows.push_back(row);
  }
  return t;
}

}  // namespace

TEST(OpenSetScores, AurocThresholdAndRocCurveCountAsStated) {
  EXPECT_DOUBLE_EQ(auroc({3, 4}, {1, 2}), 1.0);
  EXPECT_DOUBLE_EQ(auroc({1, 2}, {3, 4}), 0.0);
  EXPECT_DOUBLE_EQ(auroc({2}, {2}), 0.5);  // a tie counts half
  EXPECT_DOUBLE_EQ(auroc({1, 3}, {2}), 0.5);
  EXPECT_TRUE(std::isnan(auroc({}, {1})));
  std::vector<double> u;
  for (int i = 1; i <= 100; ++i) u.push_back(i);
  const double t = thresholdForFalseAccept(u, 0.05);
  int accepted = 0;
  for (double v : u) accepted += v >= t;
  EXPECT_EQ(accepted, 5);  // 96 … 100
  EXPECT_GT(thresholdForFalseAccept(u, 0.0), 100.0);  // none accepted
  EXPECT_EQ(errorOf([] { thresholdForFalseAccept({}, 0.05); }),
            "open-set calibration: no views of unknown categories to set the threshold on");
  const RocCurve c = rocCurve({3, 4}, {1, 4});
  ASSERT_EQ(c.false_accept.size(), 4u);  // (0,0), score 4, score 3, score 1
  EXPECT_DOUBLE_EQ(c.false_accept[1], 0.5);
  EXPECT_DOUBLE_EQ(c.true_accept[1], 0.5);
  EXPECT_DOUBLE_EQ(c.false_accept.back(), 1.0);
  EXPECT_DOUBLE_EQ(c.true_accept.back(), 1.0);
  EXPECT_EQ(errorOf([] { checkOpenSetMethod("entropy"); }),
            "open-set method 'entropy' is not one of max-probability, knn, knn-relative");
}

// The calibration test: on a small simulated set, categories never trained on are accepted
// at about the stated rate, and the known views lose little accuracy against closed-set.
class OpenSetCalibration : public ::testing::TestWithParam<std::string> {};

TEST_P(OpenSetCalibration, UnseenCategoriesAreAcceptedAtAboutTheStatedRate) {
  const int dims = 26;
  const Clusters train = clusters(16, 0, 30, dims, 1);
  const Clusters known = clusters(16, 0, 10, dims, 11);     // new views of the trained categories
  const Clusters unknown = clusters(10, 16, 60, dims, 21);  // 10 categories never trained on
  auto clf = makeClassifier(fastXgboost());
  clf->fit(train.x, train.y, 16);
  const Matrix pk = clf->predictProba(known.x), pu = clf->predictProba(unknown.x);
  const std::vector<int> best = argmaxRows(pk);
  // Binomial spread of the calibration's 480 and the test's 600 unknown views: ~1.4 points at 5 %,
  // ~2.4 at 20 %; the tolerances are about twice that.
  for (const auto& [stated, tolerance] : {std::pair{0.05, 0.03}, std::pair{0.20, 0.05}}) {
    OpenSetOptions o;
    o.methods = {GetParam()};
    o.false_accept = stated;
    const OpenSet s = calibrateOpenSets(train.x, train.y, train.category, fastXgboost(), o).front();
    EXPECT_EQ(s.method, GetParam());
    EXPECT_EQ(s.calibration_views, 16 * 30);  // every training category left out once
    EXPECT_EQ(s.calibration_groups, 5);
    const std::vector<double> ks = openSetScores(s, known.x, pk), us = openSetScores(s, unknown.x, pu);
    if (GetParam() == "knn") {
      EXPECT_NEAR(acceptedFraction(s, us), stated, tolerance) << "stated " << stated;
    } else {
      // XGBoost's probabilities saturate on separated classes: ties at the top, so max-probability
      // rejects more. knn-relative errs the same way here (measured 1.8 % at 5 %, 8.3 % at 20 %):
      // with every class equally spread its per-class scales only add their sampling noise. On the
      // simulated objects, whose classes are not alike, it holds the rate better than knn
      // (docs/results.md, "Open-set answers").
      EXPECT_LE(acceptedFraction(s, us), stated + tolerance) << "stated " << stated;
      if (GetParam() == "knn-relative") EXPECT_GT(acceptedFraction(s, us), stated / 3) << "stated " << stated;
    }
    // And the known views are accepted: a method that rejects everything meets the bars above.
    // Measured over 20 seeds of the three sets (seed, seed + 10, seed + 20; this test's is 1),
    // 2026-12-05, known views accepted at 5 % / 20 %: max-probability 0.931-0.994 (mean 0.967, sd
    // 0.017) at both, knn 0.975-1 / 0.994-1, knn-relative 0.950-1 / 0.994-1; seed 1: 0.956, 0.994 /
    // 1, 0.988 / 0.994.
    EXPECT_GT(acceptedFraction(s, ks), 0.9) << "stated " << stated;
    double closed = 0, open = 0;
    for (std::size_t i = 0; i < best.size(); ++i) {
      closed += best[i] == known.y[i];
      open += best[i] == known.y[i] && s.answerFor(ks[i]) == Answer::Class;
    }
    closed /= static_cast<double>(best.size());
    open /= static_cast<double>(best.size());
    EXPECT_GT(closed, 0.9);
    if (GetParam() != "max-probability") {  // the target: within 2 points of closed-set
      EXPECT_GT(open, closed - 0.02) << "stated " << stated;
      EXPECT_GT(auroc(ks, us), 0.97);
    } else {  // its probabilities separate less: AUROC 0.964-0.996 over the 20 seeds (mean 0.982, sd
              // 0.008; seed 1: 0.980), against 0.988-1 for the other two
      EXPECT_GT(auroc(ks, us), 0.95);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, OpenSetCalibration, ::testing::Values("knn", "knn-relative", "max-probability"));

// Classes of unequal spread (the banana and the screwdriver against the boxes): knn's raw distance
// puts a noisy known class's views far below a tight one's, so one threshold rejects the noisy
// class most of the time; knn-relative divides each distance by its class's own spread, and
// known views of both score alike.
TEST(OpenSetScores, KnnRelativeScoresNoisyAndTightKnownClassesAlike) {
  const int dims = 8, noisy_from = 4;
  const Clusters train = clusters(8, 0, 40, dims, 1, 12.f, noisy_from, 2.5f);
  const Clusters known = clusters(8, 0, 40, dims, 11, 12.f, noisy_from, 2.5f);
  auto clf = makeClassifier(fastXgboost());
  clf->fit(train.x, train.y, 8);
  const Matrix pk = clf->predictProba(known.x);
  auto medians = [&](const OpenSet& s) {
    const std::vector<double> ks = openSetScores(s, known.x, pk);
    std::vector<double> tight, noisy;
    for (std::size_t i = 0; i < ks.size(); ++i) (known.y[i] < noisy_from ? tight : noisy).push_back(ks[i]);
    for (auto* v : {&tight, &noisy}) std::nth_element(v->begin(), v->begin() + v->size() / 2, v->end());
    return std::pair{tight[tight.size() / 2], noisy[noisy.size() / 2]};
  };
  const OpenSet relative = fitOpenSetScorer("knn-relative", train.x, train.y);
  ASSERT_EQ(relative.class_scale.size(), 8u);
  for (int c = 0; c < noisy_from; ++c) {  // the noisy classes' own scale: about 2.5 × the tight ones'
    EXPECT_GT(relative.class_scale[static_cast<std::size_t>(c + noisy_from)], 1.8f * relative.class_scale[static_cast<std::size_t>(c)]);
    EXPECT_LT(relative.class_scale[static_cast<std::size_t>(c + noisy_from)], 3.5f * relative.class_scale[static_cast<std::size_t>(c)]);
  }
  const auto [knn_tight, knn_noisy] = medians(fitOpenSetScorer("knn", train.x, train.y));
  const auto [rel_tight, rel_noisy] = medians(relative);
  EXPECT_LT(knn_noisy, knn_tight - 0.1) << "knn: tight " << knn_tight << ", noisy " << knn_noisy;
  EXPECT_NEAR(rel_noisy, rel_tight, 0.05) << "knn-relative: tight " << rel_tight << ", noisy " << rel_noisy;
}

// Why a fold's false accepts stray from the stated rate (docs/results.md): an unknown object like one
// the model knows (the mustard bottle beside the sugar box) is accepted far more often than the
// pooled calibration says, because most left-out categories lie far from the rest. With a near pair
// among the training categories too (c8 and c9), the per-group rule holds the rate on each left-out
// category alone, so the near unknown (u, beside c0) is held to it as well; the pooled rule is not.
TEST(OpenSetCalibration, ThePerGroupRuleHoldsTheRateOnAnUnknownBesideAKnownCategory) {
  const int dims = 26;
  const float near = 3.f;  // centres 3 apart (unit noise): a pair the classifier mostly separates
  const auto moveBeside = [&](Clusters& c, int category_row_from, int rows, int axis_from, int axis_to) {
    for (int r = category_row_from; r < category_row_from + rows; ++r)
      c.x(r, axis_from) -= 6.f, c.x(r, axis_to) += 6.f, c.x(r, axis_from) += near;
  };
  Clusters train = clusters(10, 0, 30, dims, 3);
  moveBeside(train, 9 * 30, 30, 9, 8);  // c9 from 6·e9 to 6·e8 + 3·e9
  Clusters unknown = clusters(1, 10, 60, dims, 23);
  moveBeside(unknown, 0, 60, 10, 0);  // u from 6·e10 to 6·e0 + 3·e10
  auto clf = makeClassifier(fastXgboost());
  clf->fit(train.x, train.y, 10);
  const Matrix pu = clf->predictProba(unknown.x);
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  o.groups = 1000;  // each category left out alone
  const OpenSet pooled = calibrateOpenSets(train.x, train.y, train.category, fastXgboost(), o).front();
  o.rule = "per-group";
  const OpenSet per_group = calibrateOpenSets(train.x, train.y, train.category, fastXgboost(), o).front();
  EXPECT_EQ(pooled.rule, "pooled");
  EXPECT_EQ(per_group.rule, "per-group");
  EXPECT_EQ(per_group.calibration_groups, 10);
  EXPECT_GT(per_group.threshold, pooled.threshold);
  const double accepted_pooled = acceptedFraction(pooled, openSetScores(pooled, unknown.x, pu));
  const double accepted_per_group = acceptedFraction(per_group, openSetScores(per_group, unknown.x, pu));
  // Stated 5 %. Measured over 20 seeds of both sets (this test's seeds 3 and 23, then +1 … +19),
  // 2026-12-07: the near unknown accepted 3.3–36.7 % pooled (mean 19, ≥ 10 in 17 of 20) and 0–16.7 %
  // per group (mean 3, ≤ 7 in 19 of 20); these seeds: 15.0 % and 0 %.
  EXPECT_GE(accepted_pooled, 0.10);
  EXPECT_LE(accepted_per_group, 0.07);
  EXPECT_EQ(errorOf([&] {
              o.rule = "strictest";
              calibrateOpenSets(train.x, train.y, train.category, fastXgboost(), o);
            }),
            "open-set calibration rule 'strictest' is not one of pooled, per-group");
}

TEST(OpenSetCalibration, NeedsThreeCategories) {
  const Clusters two = clusters(2, 0, 10, 4, 1);
  EXPECT_EQ(errorOf([&] { calibrateOpenSets(two.x, two.y, two.category, fastXgboost(), {}); }),
            "open-set calibration leaves categories out of training: it needs at least 3 categories, the training "
            "views have 2");
  OpenSetOptions o;
  setOpenSetMethod(o, "auto");  // auto: a closed-set model instead
  const Model m = trainModel(tableOf(two), {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
  EXPECT_FALSE(m.info.open_set.enabled());
  EXPECT_EQ(errorOf([&] { setOpenSetMethod(o, "entropy"); }),
            "open-set method 'entropy' is not one of auto, max-probability, knn, knn-relative, none");
}

TEST(OpenSetModel, ThresholdAndReferencesSurviveTheModelFileAndAnswerUnknown) {
  const Clusters train = clusters(6, 0, 30, 8, 1);
  OpenSetOptions o;
  o.methods = {"knn"};
  const Model m = trainModel(tableOf(train), {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
  ASSERT_TRUE(m.info.open_set.enabled());
  const keyturn::test::ScratchFolder scratch("open_set_model");
  const fs::path& dir = scratch.path;
  saveModel(dir.string(), m);
  const Model back = loadModel(dir.string());
  EXPECT_EQ(back.info.open_set.method, "knn");
  EXPECT_DOUBLE_EQ(back.info.open_set.threshold, m.info.open_set.threshold);
  EXPECT_DOUBLE_EQ(back.info.open_set.false_accept, 0.05);
  EXPECT_EQ(back.info.open_set.references.rows(), 180);
  EXPECT_EQ(back.info.open_set.reference_class, m.info.open_set.reference_class);
  // A view of a trained category, one far from all of them, and one too empty to describe.
  FeatureTable t = tableOf(clusters(6, 0, 1, 8, 5));
  t.rows.resize(2);
  for (auto& v : t.rows[1].values) v = 40.f;
  FeatureRow empty;
  empty.id = "empty";
  empty.keypoints = -1;
  empty.problem = "too few keypoints: ISS found 2 in 50 points";
  empty.no_object = true;
  empty.values.assign(8, std::nanf(""));
  t.rows.push_back(empty);
  const auto before = predictRows(m, t, "m"), after = predictRows(back, t, "m");
  ASSERT_EQ(after.size(), 3u);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(after[i].score, before[i].score, 1e-4);  // references kept to 4 decimals
  EXPECT_EQ(after[0].answer, Answer::Class);
  EXPECT_EQ(answerLabel(back.info, after[0]), "c0");
  EXPECT_EQ(after[1].answer, Answer::Unknown);
  EXPECT_EQ(answerLabel(back.info, after[1]), "unknown");
  EXPECT_LT(after[1].score, back.info.open_set.threshold);
  EXPECT_EQ(after[2].answer, Answer::NoObject);
  EXPECT_EQ(answerLabel(back.info, after[2]), "no object");
}

// With every view's angle, train calibrates a turn's threshold too (turn_fusion.h): on turns of 3
// views over 90° of the categories left out in turn, one starting at every left-out view. It is
// kept in the model file; a model trained without angles has none and turns take the single
// view's threshold.
TEST(OpenSetModel, TheTurnThresholdIsCalibratedOnTurnsAndSurvivesTheModelFile) {
  const int per = 16;  // 8 views per elevation, 45° apart
  const FeatureTable t = tableOf(clusters(6, 0, per, 8, 1));
  std::vector<double> az;
  for (std::size_t r = 0; r < t.rows.size(); ++r) az.push_back(45.0 * static_cast<double>((r % per) / 2));
  OpenSetOptions o;
  o.methods = {"knn"};
  const Model m = trainModel(t, {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o, az);
  const OpenSet& s = m.info.open_set;
  ASSERT_TRUE(std::isfinite(s.turn_threshold));
  EXPECT_EQ(s.calibration_turns, 6 * per);  // every view of a full turn starts one
  EXPECT_NE(s.turn_threshold, s.threshold);  // a mean of 3 scores spreads less than one
  EXPECT_DOUBLE_EQ(s.thresholdFor(1), s.threshold);
  EXPECT_DOUBLE_EQ(s.thresholdFor(3), s.turn_threshold);
  const keyturn::test::ScratchFolder scratch("open_set_turns");
  saveModel(scratch.path.string(), m);
  EXPECT_DOUBLE_EQ(loadModel(scratch.path.string()).info.open_set.turn_threshold, s.turn_threshold);
  EXPECT_EQ(loadModel(scratch.path.string()).info.open_set.calibration_turns, 6 * per);
  // Without angles (or with one missing): no turn threshold.
  EXPECT_TRUE(std::isnan(trainModel(t, {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o).info.open_set.turn_threshold));
  az[3] = std::nan("");
  EXPECT_TRUE(std::isnan(trainModel(t, {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o, az).info.open_set.turn_threshold));
  EXPECT_EQ(errorOf([&] { trainModel(t, {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o, {1.0}); }),
            "training: 96 views but 1 angles");
}

TEST(OpenSetModel, KnnRelativeClassScalesSurviveTheModelFile) {
  const Clusters train = clusters(6, 0, 30, 8, 1, 6.f, 3, 2.f);
  OpenSetOptions o;
  o.methods = {"knn-relative"};
  const Model m = trainModel(tableOf(train), {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
  ASSERT_EQ(m.info.open_set.class_scale.size(), 6u);
  const keyturn::test::ScratchFolder scratch("knn_relative_model");
  const std::filesystem::path& dir = scratch.path;
  saveModel(dir.string(), m);
  const Model back = loadModel(dir.string());
  EXPECT_EQ(back.info.open_set.method, "knn-relative");
  EXPECT_EQ(back.info.open_set.class_scale, m.info.open_set.class_scale);
  const FeatureTable t = tableOf(clusters(6, 0, 2, 8, 5, 6.f, 3, 2.f));
  const auto before = predictRows(m, t, "m"), after = predictRows(back, t, "m");
  for (std::size_t i = 0; i < t.rows.size(); ++i) EXPECT_NEAR(after[i].score, before[i].score, 1e-3);
  // A sidecar whose class_scale does not fit the classes is named.
  nlohmann::json sidecar = nlohmann::json::parse(keyturn::test::readText(dir / "model.json"));
  sidecar["open_set"]["class_scale"] = {1.0, 2.0};
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  EXPECT_EQ(errorOf([&] { loadModel(dir.string()); }),
            (dir / "model.json").string() + ": open_set: knn-relative needs class_scale of 6 values");
  fs::remove_all(dir);
}

TEST(OpenSetModel, AModelWithoutOpenSetStaysClosedSet) {
  // The shipped studio model as it was before issue 34: its sidecar without open_set.
  const fs::path source = fs::path(KEYTURN_DATA_DIR) / "models/sim-objects";
  EXPECT_EQ(loadModel(source.string()).info.open_set.method, "knn-relative");
  const keyturn::test::ScratchFolder scratch("closed_set_model");
  const std::filesystem::path& dir = scratch.made();
  nlohmann::json sidecar = nlohmann::json::parse(keyturn::test::readText(source / "model.json"));
  sidecar.erase("open_set");
  sidecar.erase("pose_references");
  keyturn::test::writeText(dir / "model.json", sidecar.dump());
  fs::copy_file(source / "model.xgb.json", dir / "model.xgb.json", fs::copy_options::overwrite_existing);
  const Model shipped = loadModel(dir.string());
  EXPECT_FALSE(shipped.info.open_set.enabled());
  FeatureTable t = modelLayout(shipped, "shipped");
  FeatureRow far;
  far.id = "far";
  far.keypoints = 30;
  far.values.assign(static_cast<std::size_t>(t.width()), 1.f);  // like nothing it was trained on
  t.rows.push_back(far);
  const auto p = predictRows(shipped, t, "shipped");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].answer, Answer::Class);  // closed-set: a class, whatever the view
  EXPECT_TRUE(std::isnan(p[0].score));
  EXPECT_EQ(answerLabel(shipped.info, p[0]), shipped.info.classes.at(static_cast<std::size_t>(p[0].best)));
}

TEST(OpenSetModel, ABadOpenSetInASidecarIsNamed) {
  const Clusters train = clusters(4, 0, 10, 4, 1);
  OpenSetOptions o;
  o.methods = {"max-probability"};
  const Model m = trainModel(tableOf(train), {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
  const keyturn::test::ScratchFolder scratch("open_set_bad");
  const fs::path& dir = scratch.path;
  saveModel(dir.string(), m);
  nlohmann::json sidecar = nlohmann::json::parse(keyturn::test::readText(dir / "model.json"));
  ASSERT_EQ(sidecar.at("open_set").at("method"), "max-probability");
  sidecar["open_set"]["method"] = "entropy";
  EXPECT_EQ(errorOf([&] { parseModelSidecar(sidecar.dump(), "m/model.json"); }),
            "m/model.json: open_set: open-set method 'entropy' is not one of max-probability, knn, knn-relative");
  // The calibration rule: absent (every model before 2026-12-07) reads pooled, per-group is kept, another is named.
  sidecar["open_set"]["method"] = "max-probability";
  EXPECT_FALSE(sidecar["open_set"]["calibration"].contains("rule"));
  EXPECT_EQ(parseModelSidecar(sidecar.dump(), "m/model.json").open_set.rule, "pooled");
  sidecar["open_set"]["calibration"]["rule"] = "per-group";
  EXPECT_EQ(parseModelSidecar(sidecar.dump(), "m/model.json").open_set.rule, "per-group");
  sidecar["open_set"]["calibration"]["rule"] = "median";
  EXPECT_EQ(errorOf([&] { parseModelSidecar(sidecar.dump(), "m/model.json"); }),
            "m/model.json: open_set: open-set calibration rule 'median' is not one of pooled, per-group");
}

TEST(OpenSetModel, DegenerateFeaturesGetAClearAnswer) {
  const Clusters train = clusters(5, 0, 20, 6, 1);
  for (const std::string method : {"knn", "max-probability"}) {
    OpenSetOptions o;
    o.methods = {method};
    const Model m = trainModel(tableOf(train), {"kpd2"}, LabelKind::Category, fastXgboost(), nullptr, o);
    FeatureTable t = tableOf(clusters(5, 0, 1, 6, 9));
    t.rows.resize(2);
    for (auto& v : t.rows[0].values) v = std::nanf("");  // every value missing
    t.rows[1].values[2] = std::nanf("");                    // one missing
    for (const auto& p : predictRows(m, t, "m")) {
      EXPECT_NE(p.answer, Answer::NoObject);
      EXPECT_TRUE(std::isfinite(p.score)) << method << " row " << p.row;
      EXPECT_GE(p.best, 0);
    }
    // All probabilities NaN (a classifier that could not say): unknown, score 0.
    Matrix x = Matrix::Zero(1, 6), nan_p = Matrix::Constant(1, 5, std::nanf(""));
    const Prediction p = predictionOf(m.info, x, nan_p);
    EXPECT_EQ(p.answer, Answer::Unknown) << method;
    EXPECT_EQ(p.score, 0.0);
  }
}

TEST(OpenSetModel, AViewTooEmptyToDescribeIsNoObject) {
  Model m;
  DescriptorOptions o;
  m.info.spec = featureSpec(o);
  m.info.blocks = {"kpd2"};
  m.info.inputs = o.histogram.bins;
  m.info.classes = {"a", "b"};
  m.classifier = makeClassifier(m.info.params);
  FeatureTable t = modelLayout(m, "m");
  Cloud two;  // K < 3: two points
  two.points = {{0.f, 0.f, 0.5f}, {0.01f, 0.f, 0.5f}};
  two.width = 2;
  t.rows.push_back(describeCloud(two, modelOptions(m, "m"), t));
  EXPECT_TRUE(t.rows[0].no_object);
  EXPECT_EQ(t.rows[0].keypoints, -1);
  const auto p = predictRows(m, t, "m");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].answer, Answer::NoObject);
  EXPECT_EQ(p[0].best, -1);
  Cloud none;
  EXPECT_THROW(Recognizer(DescriptorOptions()).describe(none), EmptyViewError);
}

TEST(OpenSetProtocol, FoldsLeaveWholeCategoriesOutAndTestEachKnownElevation) {
  const FeatureTable t = tableOf(clusters(7, 0, 6, 4, 1));
  const Protocol p = makeProtocol("open-set3", t, 7);
  ASSERT_EQ(p.folds.size(), 3u);
  std::map<std::string, int> unknown_in;
  for (const Fold& f : p.folds) {
    std::set<std::string> left_out, trained;
    for (auto r : f.unknown) left_out.insert(t.rows[r].cls);
    for (auto r : f.train) {
      trained.insert(t.rows[r].cls);
      EXPECT_EQ(left_out.count(t.rows[r].cls), 0u);
    }
    for (auto r : f.test) {
      EXPECT_EQ(left_out.count(t.rows[r].cls), 0u);
      EXPECT_EQ(trained.count(t.rows[r].cls), 1u);
    }
    std::set<std::string> tested_elevations, trained_elevations;
    for (auto r : f.test) tested_elevations.insert(t.rows[r].elevation);
    for (auto r : f.train) trained_elevations.insert(t.rows[r].elevation);
    EXPECT_EQ(tested_elevations.size(), 1u);
    EXPECT_EQ(trained_elevations.count(*tested_elevations.begin()), 0u);
    EXPECT_EQ(f.train.size() + f.test.size() + f.unknown.size(), t.rows.size());
    for (const auto& c : left_out) ++unknown_in[c];
  }
  EXPECT_EQ(unknown_in.size(), 7u);  // every category is an unknown once
  for (const auto& [c, n] : unknown_in) EXPECT_EQ(n, 1) << c;
  EXPECT_EQ(errorOf([&] { makeProtocol("open-set", tableOf(clusters(2, 0, 4, 4, 1)), 7); }),
            "open-set folds leave categories out: they need at least 3 categories (the data has 2)");
}

TEST(OpenSetProtocol, AFoldReportsFalseAcceptsAndKnownAccuracyBesideClosedSet) {
  const FeatureTable t = tableOf(clusters(12, 0, 20, 12, 1));
  const Protocol p = makeProtocol("open-set4", t, 7, LabelKind::Category);
  OpenSetOptions o;
  o.methods = openSetMethods();
  std::vector<FoldOutcome> folds;
  for (const Fold& f : p.folds) folds.push_back(evaluateOpenSetFold(t, {"kpd2"}, p.labels.of_row, f, fastXgboost(), o));
  const auto s = summariseOpenSet(folds);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].method, "max-probability");
  EXPECT_EQ(s[1].method, "knn");
  EXPECT_EQ(s[2].method, "knn-relative");
  EXPECT_EQ(s[1].unknown_views, 240u);  // every view is an unknown in one fold
  EXPECT_EQ(s[1].known_views, 360u);    // 4 folds × 9 known categories × the 10 views at its elevation
  EXPECT_GT(s[1].auroc_mean, 0.95);
  EXPECT_LT(s[1].false_accept, 0.15);
  EXPECT_GT(s[1].known_accuracy_closed, 0.9);
  EXPECT_LE(s[1].known_accuracy_open, s[1].known_accuracy_closed);
  EXPECT_NEAR(s[1].known_accuracy_open, s[1].known_accuracy_closed, 0.1);
  EXPECT_EQ(s[1].known_scores.size(), 360u);
}

// The open-set protocol's turns: each fold's views read as an object turning (3 views over 90°),
// fused by pose. The clusters overlap (spread 4), so single views err, and are rejected (most are
// accepted) independently from view to view: three views must then be right and accepted more
// often, and unknowns accepted less often, than one (the majority rule leans the way most views do).
TEST(OpenSetProtocol, AFoldReadAsTurnsOfTheTableFusesThreeViewsOfEachObject) {
  const int per = 16;  // 8 views per elevation, 45° apart
  const FeatureTable t = tableOf(clusters(12, 0, per, 12, 3, 4.0f));
  std::vector<double> az;
  for (std::size_t r = 0; r < t.rows.size(); ++r) az.push_back(45.0 * static_cast<double>((r % per) / 2));
  const Protocol p = makeProtocol("open-set4", t, 7, LabelKind::Category);
  OpenSetOptions o;
  o.methods = {"knn"};
  std::vector<FoldOutcome> turning, single;
  for (const Fold& f : p.folds) {
    turning.push_back(evaluateOpenSetFold(t, {"kpd2"}, p.labels.of_row, f, fastXgboost(), o, {}, az));
    single.push_back(evaluateOpenSetFold(t, {"kpd2"}, p.labels.of_row, f, fastXgboost(), o));
  }
  const OpenSetSummary s = summariseOpenSet(turning).at(0);
  // A turn starts at every view of a held-out capture group (8 views, wrapping round): 4 folds ×
  // 9 known categories × 8 at the tested elevation; 3 unknown categories × 2 elevations × 8.
  EXPECT_EQ(s.fused_known, 4u * 9u * 8u);
  EXPECT_EQ(s.fused_unknown, 4u * 3u * 2u * 8u);
  EXPECT_LT(s.known_accuracy_closed, 0.9);  // single views do err
  EXPECT_GT(s.fused_known_accuracy_closed, s.known_accuracy_closed + 0.05);
  EXPECT_GT(s.fused_known_accuracy_open, s.known_accuracy_open + 0.05);
  EXPECT_GT(s.false_accept, 0.02);
  // Turns are held to the stated rate as single views are: the turn threshold is calibrated on
  // turns of the training categories left out in turn, as the single views' threshold on their
  // views. So the turns' false accepts land near the single views' (12.0 and 13.5 % here, both
  // above the stated 5 % on these clusters; binomial spread ~2.4 points over 192 turns), where the
  // former uncalibrated vote (and the mean held to the single view's threshold: 1.6 %) traded
  // known turns for fewer; the known turns are named far more often than single views.
  EXPECT_NEAR(s.fused_false_accept, s.false_accept, 0.05);
  EXPECT_LE(s.fused_known_accuracy_open, s.fused_known_accuracy_closed);
  // The single views' figures do not depend on the angles; without them there are no turns.
  const OpenSetSummary alone = summariseOpenSet(single).at(0);
  EXPECT_DOUBLE_EQ(alone.known_accuracy_open, s.known_accuracy_open);
  EXPECT_DOUBLE_EQ(alone.false_accept, s.false_accept);
  EXPECT_EQ(alone.fused_known, 0u);
  EXPECT_TRUE(std::isnan(alone.fused_false_accept));
  EXPECT_EQ(errorOf([&] {
              evaluateOpenSetFold(t, {"kpd2"}, p.labels.of_row, p.folds[0], fastXgboost(), o, {}, {1.0, 2.0});
            }),
            "open-set fold '" + p.folds[0].name + "': " + std::to_string(t.rows.size()) + " views but 2 azimuths");
}

// The report's false accepts by fold (docs/results.md: which categories are unknown decides a fold's
// rate): each fold's own share, beside the pooled rate, counted by hand.
TEST(OpenSetProtocol, FalseAcceptsAreReportedFoldByFoldBesideThePooledRate) {
  std::vector<FoldOutcome> folds(3);
  const std::size_t unknown[] = {10, 30, 20}, accepted[] = {3, 0, 5};
  for (std::size_t k = 0; k < folds.size(); ++k) {
    folds[k].test_views = 4;
    folds[k].unknown_views = unknown[k];
    OpenSetFoldOutcome o;
    o.method = "knn-relative";
    o.unknown_accepted = accepted[k];
    o.known_scores = {0.9, 0.8, 0.7, 0.6};
    o.unknown_scores.assign(unknown[k], 0.1);
    folds[k].open_set.push_back(o);
  }
  const std::vector<OpenSetSummary> s = summariseOpenSet(folds);
  ASSERT_EQ(s.size(), 1u);
  ASSERT_EQ(s[0].false_accept_by_fold.size(), 3u);
  EXPECT_DOUBLE_EQ(s[0].false_accept_by_fold[0], 0.3);
  EXPECT_DOUBLE_EQ(s[0].false_accept_by_fold[1], 0.0);
  EXPECT_DOUBLE_EQ(s[0].false_accept_by_fold[2], 0.25);
  EXPECT_DOUBLE_EQ(s[0].false_accept, 8.0 / 60.0);  // pooled: each fold weighed by its unknown views
}
