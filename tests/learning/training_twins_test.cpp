// Training-side augmentation (evaluate --train-extra): twins matched to their views by id, and
// trained on only where their view is — a fold never sees the twin of a view it tests.
#include <gtest/gtest.h>

#include <random>

#include "keyturn/learning/evaluation_report.h"
#include "keyturn/learning/training_twins.h"
#include "support/error_of.h"

using namespace keyturn::learning;
using keyturn::test::errorOf;

namespace {

// n views of one class in two instances at random, each with its own random 8-value block: there
// is nothing to learn, only views to remember.
FeatureTable rememberOnly(std::size_t n) {
  FeatureTable t;
  t.blocks = {"kpd2"};
  t.sizes = {8};
  t.spec = {{"bins", "8"}};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (std::size_t v = 0; v < n; ++v) {
    FeatureRow r;
    r.id = "x/view" + std::to_string(v);
    r.cls = "x";
    r.instance = u(rng) < 0.5f ? "a" : "b";
    r.elevation = "30";
    r.keypoints = 20;
    for (int k = 0; k < 8; ++k) r.values.push_back(u(rng));
    t.rows.push_back(r);
  }
  return t;
}

}  // namespace

TEST(TrainingTwins, MatchedByIdAndABadExtraIsNamed) {
  FeatureTable t = rememberOnly(6);
  FeatureTable extra = t;
  extra.rows = {t.rows[4], t.rows[1], t.rows[4]};  // two twins of view 4, one of view 1
  const TwinRows twins = appendTwins(t, extra, "jittered");
  ASSERT_EQ(t.rows.size(), 9u);
  ASSERT_EQ(twins.size(), 6u);
  EXPECT_EQ(twins[4], (std::vector<std::size_t>{6, 8}));
  EXPECT_EQ(twins[1], (std::vector<std::size_t>{7}));
  EXPECT_TRUE(twins[0].empty());
  EXPECT_EQ(withTwins({1, 4}, twins), (std::vector<std::size_t>{1, 4, 7, 6, 8}));
  EXPECT_EQ(labelsWithTwins({0, 1, 0, 1, 1, 0}, twins), (std::vector<int>{0, 1, 0, 1, 1, 0, 1, 1, 1}));

  FeatureTable base = rememberOnly(6);
  FeatureTable stranger = base;
  stranger.rows = {base.rows[0]};
  stranger.rows[0].id = "x/view99";
  EXPECT_EQ(errorOf([&] { appendTwins(base, stranger, "jittered"); }), "jittered: view x/view99 is not a view of the dataset");
  stranger.rows[0] = base.rows[2];
  stranger.rows[0].instance = base.rows[2].instance == "a" ? "b" : "a";
  EXPECT_EQ(errorOf([&] { appendTwins(base, stranger, "jittered"); }),
            "jittered: view x/view2 is x/" + stranger.rows[0].instance + ", in the dataset x/" + base.rows[2].instance);
  FeatureTable other_bins = base;
  other_bins.spec["bins"] = "16";
  EXPECT_EQ(errorOf([&] { appendTwins(base, other_bins, "jittered"); }),
            "jittered: described with other parameters (bins 16, the dataset's 8)");
  other_bins = base;
  other_bins.blocks = {"esf"};
  EXPECT_EQ(errorOf([&] { appendTwins(base, other_bins, "jittered"); }), "jittered: its features have other blocks than the dataset's");
  EXPECT_EQ(base.rows.size(), 6u) << "a refused extra leaves the table as it was";
}

// Twins identical to their views: a classifier that remembers its training views scores on a test
// view only if it trained on that view's twin. Through evaluate's run it stays near chance; the
// same fold trained on its test views' twins (the leak the rule prevents) scores far above it.
TEST(TrainingTwins, ATwinIsTrainedOnOnlyWhereItsViewIs) {
  const FeatureTable t = rememberOnly(240);
  EvaluationPlan plan;
  plan.dataset = "random views";
  plan.feature_sets = {"kpd2"};
  plan.classifiers = {"xgboost"};
  plan.protocols = {"kfold4"};
  plan.bins = {8};
  plan.params.xgboost.rounds = 60;
  plan.params.xgboost.threads = 1;
  plan.jobs = 2;
  plan.train_extra = {"copies"};
  EvaluationRun run =
      prepareEvaluation(plan, [&](int) { return t; }, [&](const std::string& name, int) {
        EXPECT_EQ(name, "copies");
        return t;
      });
  evaluateRows(run);
  ASSERT_EQ(run.rows.size(), 1u);
  const Evaluation& ev = run.rows[0].ev;
  ASSERT_EQ(ev.folds.size(), 4u);
  for (const auto& f : ev.folds) {
    EXPECT_EQ(f.train_views, 180u);
    EXPECT_EQ(f.twin_views, 180u) << "every training view brings its twin, no test view does";
    EXPECT_EQ(f.test_views, 60u);
  }
  EXPECT_LT(ev.mean(), 0.7) << "nothing to learn: near chance";

  const Fold& fold = run.rows[0].proto->folds[0];
  Fold leaking = fold;
  for (std::size_t r : fold.test) leaking.train.push_back(run.twins.at(8)[r].front());
  const FoldOutcome leaked =
      evaluateFold(run.tables.at(8), {"kpd2"}, run.rows[0].proto->labels.of_row, 2, leaking, plan.params);
  EXPECT_GT(leaked.accuracy(), 0.9) << "the test can fail: a fold trained on its test views' twins remembers them";

  const EvaluationReport report = evaluationReport(run);
  EXPECT_NE(report.markdown.find("240 views; ISS keypoints"), std::string::npos) << "the summary counts the dataset's own views";
  EXPECT_NE(report.markdown.find("Training augmented by 240 twin views from `copies`"), std::string::npos) << report.markdown;
  EXPECT_NE(report.json.find("\"twin_views\": 180"), std::string::npos);
  EXPECT_NE(report.json.find("\"train_extra\""), std::string::npos);
}
