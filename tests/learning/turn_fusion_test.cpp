// A turn's answer (issue 48): one rule, TurnFusion's, whichever way the views arrive —
// classify --fuse (fusePredictions), evaluate's open-set turns (fusedTurnClass) and the studio's
// live fusion (LiveFusion) answer the same sequences alike.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "keyturn/learning/live_fusion.h"
#include "keyturn/learning/model_fusion.h"
#include "keyturn/learning/open_set_evaluation.h"
#include "keyturn/learning/turn_fusion.h"

using namespace keyturn::learning;

namespace {

OpenSet knnAt(double threshold) {
  OpenSet s;
  s.method = "knn";
  s.threshold = threshold;
  return s;
}

FusionOptions independent() {
  FusionOptions o;
  o.method = "independent";
  return o;
}

struct Step {
  Answer answer;
  double score;
  std::vector<float> p;
};

TurnFusion fed(const std::vector<Step>& steps, const OpenSet& s) {
  TurnFusion t(independent(), s);
  double az = 0;
  for (const auto& v : steps) t.add({v.answer, v.score, v.p, az += 10, {}});
  return t;
}

}  // namespace

TEST(TurnFusion, NoObjectViewsAreNotViewsOfTheObject) {
  const TurnFusion none = fed({{Answer::NoObject, 0, {}}, {Answer::NoObject, 0, {}}}, knnAt(0.4));
  EXPECT_EQ(none.views(), 0u);
  EXPECT_EQ(none.answer(), Answer::NoObject);
  EXPECT_EQ(none.best(), -1);
  const TurnFusion t = fed({{Answer::NoObject, 0, {}}, {Answer::NoObject, 0, {}}, {Answer::Unknown, 0.3, {0.5f, 0.5f}},
                            {Answer::Class, 0.6, {0.1f, 0.9f}}},
                           knnAt(0.4));
  EXPECT_EQ(t.views(), 2u);
  EXPECT_EQ(t.unknownViews(), 1u);
  EXPECT_EQ(t.answer(), Answer::Class);  // mean 0.45 of the two views of the object
  EXPECT_EQ(t.best(), 1);
}

TEST(TurnFusion, AllViewsUnknownIsUnknownWithoutABelief) {
  const TurnFusion t = fed({{Answer::Unknown, 0.1, {0.5f, 0.5f}}, {Answer::Unknown, 0.35, {0.9f, 0.1f}}}, knnAt(0.4));
  EXPECT_EQ(t.answer(), Answer::Unknown);
  EXPECT_TRUE(t.belief().empty());
  EXPECT_FALSE(t.certain());
}

// The studio's CI failure (stop 53): the drill turned 0° → 90° with the remade model. End-on, from
// 65° on, its single views score under the threshold; 3 of the 6 views a slow machine took were
// those. A vote ("unknown" while half the views are) called the known drill unknown; the mean
// score of the turn names it. An unseen object with one false accept among its views stays unknown.
TEST(TurnFusion, TheMeanScoreDecidesNotAVote) {
  const OpenSet s = knnAt(0.397);
  const TurnFusion drill = fed({{Answer::Class, 0.60, {0.1f, 0.9f}},
                                {Answer::Class, 0.55, {0.2f, 0.8f}},
                                {Answer::Class, 0.44, {0.3f, 0.7f}},
                                {Answer::Unknown, 0.31, {0.6f, 0.4f}},
                                {Answer::Unknown, 0.29, {0.5f, 0.5f}},
                                {Answer::Unknown, 0.25, {0.5f, 0.5f}}},
                               s);
  EXPECT_EQ(drill.unknownViews(), 3u);
  EXPECT_EQ(drill.answer(), Answer::Class);  // mean 0.407
  EXPECT_EQ(drill.best(), 1);
  const TurnFusion unseen = fed({{Answer::Class, 0.45, {0.9f, 0.1f}}, {Answer::Unknown, 0.20, {0.6f, 0.4f}},
                                 {Answer::Unknown, 0.15, {0.5f, 0.5f}}},
                                s);
  EXPECT_EQ(unseen.answer(), Answer::Unknown);  // mean 0.267
  EXPECT_FALSE(unseen.belief().empty());       // the false accept's belief is there, and unknown
  // A NaN score (it could not be computed) counts as 0, never as known.
  EXPECT_EQ(fed({{Answer::Class, 0.5, {0.1f, 0.9f}}, {Answer::Unknown, std::nan(""), {0.5f, 0.5f}}}, s).answer(),
            Answer::Unknown);
}

// A model with a turn threshold holds a turn of two or more views to it, a single view to its own.
TEST(TurnFusion, ATurnOfSeveralViewsIsHeldToTheTurnThreshold) {
  OpenSet s = knnAt(0.40);
  s.turn_threshold = 0.30;
  EXPECT_EQ(fed({{Answer::Unknown, 0.35, {0.2f, 0.8f}}}, s).answer(), Answer::Unknown);
  EXPECT_EQ(fed({{Answer::Unknown, 0.35, {0.2f, 0.8f}}, {Answer::Unknown, 0.35, {0.2f, 0.8f}}}, s).answer(),
            Answer::Unknown);  // no view named: no class evidence to answer with
  const TurnFusion t = fed({{Answer::Class, 0.42, {0.2f, 0.8f}}, {Answer::Unknown, 0.22, {0.5f, 0.5f}}}, s);
  EXPECT_EQ(t.answer(), Answer::Class);  // mean 0.32 >= 0.30
  s.turn_threshold = std::nan("");       // a model without one: the single view's
  EXPECT_EQ(fed({{Answer::Class, 0.42, {0.2f, 0.8f}}, {Answer::Unknown, 0.22, {0.5f, 0.5f}}}, s).answer(), Answer::Unknown);
}

TEST(TurnFusion, ClosedSetTakesEveryViewAndStopsWhenCertain) {
  OpenSet closed;
  FusionOptions o = independent();
  o.stop_belief = 0.95;
  TurnFusion t(o, closed);
  t.add({Answer::Class, 0, {0.2f, 0.8f}, 0, {}});
  EXPECT_FALSE(t.certain());
  t.add({Answer::Unknown, 0, {0.1f, 0.9f}, 10, {}});  // a closed-set model has no unknown: evidence all the same
  EXPECT_NEAR(t.belief()[1], 0.72 / (0.72 + 0.02), 1e-6);
  EXPECT_EQ(t.answer(), Answer::Class);
  EXPECT_TRUE(t.certain());
}

// The same sequences through the three callers give the same answers.
TEST(TurnFusion, ClassifyEvaluateAndTheStudioAnswerTheSameSequencesAlike) {
  Model m;
  m.info.classes = {"a", "b", "c"};
  m.info.open_set = knnAt(0.4);
  const std::vector<std::vector<Step>> sequences = {
      {{Answer::NoObject, 0, {}}, {Answer::NoObject, 0, {}}, {Answer::Unknown, 0.3, {0.4f, 0.3f, 0.3f}}, {Answer::Class, 0.6, {0.1f, 0.1f, 0.8f}}},
      {{Answer::Class, 0.45, {0.7f, 0.2f, 0.1f}}, {Answer::Unknown, 0.1, {0.3f, 0.3f, 0.4f}}, {Answer::Unknown, 0.2, {0.2f, 0.5f, 0.3f}}},
      {{Answer::Class, 0.5, {0.6f, 0.3f, 0.1f}}, {Answer::Class, 0.5, {0.2f, 0.7f, 0.1f}}, {Answer::Unknown, 0.35, {0.3f, 0.3f, 0.4f}}},
      {{Answer::Unknown, 0.2, {0.3f, 0.3f, 0.4f}}},
  };
  for (std::size_t k = 0; k < sequences.size(); ++k) {
    const auto& seq = sequences[k];
    // classify --fuse
    std::vector<Prediction> preds;
    std::vector<double> az;
    // evaluate's turns take only the views its folds hold (described ones: "no object" has none)
    std::vector<FusionView> views;
    std::vector<double> scores;
    LiveFusion live(m.info);
    for (std::size_t i = 0; i < seq.size(); ++i) {
      Prediction p;
      p.row = i;
      p.answer = seq[i].answer;
      p.score = seq[i].score;
      p.probabilities = seq[i].p;
      p.best = p.probabilities.empty() ? -1 : 0;
      preds.push_back(p);
      az.push_back(10.0 * static_cast<double>(i));
      if (seq[i].answer != Answer::NoObject) {
        views.push_back({seq[i].p, az.back(), {}});
        scores.push_back(seq[i].score);
      }
      live.add(seq[i].answer, seq[i].score, seq[i].p, {}, az.back());
    }
    const ModelFusion classify = fusePredictions(m, FeatureTable(), preds, az, independent());
    const Answer a = classify.steps.back().answer;
    const int c = a == Answer::Class ? classify.steps.back().best : -1;
    const int evaluated = fusedTurnClass(views, scores, m.info.open_set, independent());
    SCOPED_TRACE("sequence " + std::to_string(k + 1));
    EXPECT_EQ(live.answer(), a);
    EXPECT_EQ(live.answer() == Answer::Class ? live.best() : -1, c);
    EXPECT_EQ(evaluated, c);
    EXPECT_EQ(live.views(), views.size());
  }
  // What they answer: sequence 1 the class c (2 views, mean 0.45), 2 unknown (0.25), 3 class a or
  // b (0.45), 4 unknown.
}
