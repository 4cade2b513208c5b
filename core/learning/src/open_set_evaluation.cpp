#include "keyturn/learning/open_set_evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "keyturn/core/error.h"
#include "keyturn/learning/fusion_evaluation.h"
#include "keyturn/learning/turn_fusion.h"
#include "fold_views.h"

namespace keyturn::learning {
namespace {

// One side of a fold (its known test views or its unknown views) as fusion sees it: each view's
// probabilities, angle and pose evidence, and each capture group's views by angle.
struct TurningViews {
  std::vector<FusionView> views;
  std::vector<std::string> group;  // each view's capture group
};

TurningViews turningViews(const FeatureTable& t, const std::vector<std::size_t>& rows, const Matrix& x,
                          const Matrix& p, const PoseReferences& refs, const std::vector<double>& az) {
  TurningViews out;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    FusionView v;
    v.probabilities.assign(p.row(row).data(), p.row(row).data() + p.cols());
    v.azimuth_deg = az[rows[k]];
    if (std::isfinite(v.azimuth_deg)) v.pose = poseEvidence(refs, x.row(row));
    out.views.push_back(std::move(v));
    out.group.push_back(detail::captureGroupOf(t.rows[rows[k]]));
  }
  return out;
}

// Each turn's views (indices into tv.views): one starting at every view whose group has all of it.
std::vector<std::vector<int>> turnsOf(const TurningViews& tv) {
  std::vector<double> az;
  for (const auto& v : tv.views) az.push_back(v.azimuth_deg);
  return learning::turnsOf(az, tv.group);
}

// The fused answer of a sequence: the class index, or -1 for "unknown" (closed-set without scores).
int fusedClass(const TurningViews& tv, const std::vector<int>& seq, const OpenSet& scorer = OpenSet(),
               const std::vector<double>* scores = nullptr) {
  std::vector<FusionView> views;
  std::vector<double> seq_scores;
  for (int i : seq) {
    views.push_back(tv.views[static_cast<std::size_t>(i)]);
    seq_scores.push_back(scores ? (*scores)[static_cast<std::size_t>(i)] : 0.0);
  }
  return fusedTurnClass(views, seq_scores, scorer);
}

}  // namespace

int fusedTurnClass(const std::vector<FusionView>& views, const std::vector<double>& scores, const OpenSet& scorer,
                   const FusionOptions& options) {
  if (scores.size() != views.size())
    throw Error("fusion: " + std::to_string(views.size()) + " views but " + std::to_string(scores.size()) + " scores");
  TurnFusion turn(options, scorer);
  for (std::size_t i = 0; i < views.size(); ++i)
    turn.add({scorer.answerFor(scores[i]), scores[i], views[i].probabilities, views[i].azimuth_deg, views[i].pose});
  return turn.answer() == Answer::Class ? turn.best() : -1;
}

FoldOutcome evaluateOpenSetFold(const FeatureTable& table, const std::vector<std::string>& blocks,
                                const std::vector<int>& labels, const Fold& fold, const ClassifierParams& params,
                                const OpenSetOptions& options, const TwinRows& twins,
                                const std::vector<double>& az) {
  if (fold.unknown.empty()) throw Error("fold '" + fold.name + "' has no unknown views (not an open-set fold)");
  const std::vector<std::size_t> train = withTwins(fold.train, twins);
  FoldOutcome out = startFoldOutcome(fold, train);
  out.unknown_views = fold.unknown.size();
  std::vector<int> y, present;
  std::vector<std::string> categories;
  for (auto r : train) y.push_back(labels.at(r)), categories.push_back(table.rows.at(r).cls);
  const std::vector<int> compact = compactClasses(y, &present);
  const int classes = static_cast<int>(present.size());
  if (classes < 2) throw Error("fold '" + fold.name + "' trains on fewer than two classes");
  checkOpenSetDistanceFor(options.distance, blocks);
  checkOpenSetMethodsFor(options.methods, blocks);
  const Matrix xtrain = table.select(blocks, train);
  const auto t0 = std::chrono::steady_clock::now();
  auto clf = makeClassifier(params);
  clf->fit(xtrain, compact, classes);
  const auto t1 = std::chrono::steady_clock::now();
  const Matrix xknown = table.select(blocks, fold.test), xunknown = table.select(blocks, fold.unknown);
  const Matrix pknown = clf->predictProba(xknown), punknown = clf->predictProba(xunknown);
  const std::vector<int> best = argmaxRows(pknown);
  out.train_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  out.predict_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  std::vector<bool> right(fold.test.size());
  std::map<std::pair<int, int>, int> cells;
  for (std::size_t k = 0; k < fold.test.size(); ++k) {
    const int truth = labels[fold.test[k]], predicted = present[static_cast<std::size_t>(best[k])];
    right[k] = predicted == truth;
    out.correct += right[k];
    ++cells[{truth, predicted}];
  }
  for (const auto& [tp, n] : cells) out.confusion.push_back({tp.first, tp.second, n});
  // The turns: pose references from the training views with an angle (twins have none).
  if (!az.empty() && az.size() != table.rows.size())
    throw Error("open-set fold '" + fold.name + "': " + std::to_string(table.rows.size()) + " views but " +
                std::to_string(az.size()) + " azimuths");
  std::vector<std::size_t> posed;
  std::vector<int> posed_y;
  std::vector<double> posed_az;
  std::vector<std::string> posed_group;
  for (std::size_t k = 0; k < train.size() && !az.empty(); ++k)
    if (std::isfinite(az[train[k]])) {
      posed.push_back(train[k]), posed_y.push_back(compact[k]), posed_az.push_back(az[train[k]]);
      posed_group.push_back(detail::captureGroupOf(table.rows[train[k]]));
    }
  TurningViews known, unknown;
  if (!posed.empty()) {
    const PoseReferences refs =
        fitPoseReferences(table.select(blocks, posed), posed_y, posed_az, posed_group, classes, FusionOptions().bin_deg);
    known = turningViews(table, fold.test, xknown, pknown, refs, az);
    unknown = turningViews(table, fold.unknown, xunknown, punknown, refs, az);
  }
  const std::vector<std::vector<int>> known_turns = turnsOf(known), unknown_turns = turnsOf(unknown);
  const auto truthOf = [&](const std::vector<int>& seq) { return labels[fold.test[static_cast<std::size_t>(seq[0])]]; };
  out.fused_known = known_turns.size();
  out.fused_unknown = unknown_turns.size();
  for (const auto& seq : known_turns) {
    const int c = fusedClass(known, seq);
    out.fused_known_closed_correct += c >= 0 && present[static_cast<std::size_t>(c)] == truthOf(seq);
  }
  // The turn threshold calibrated as train calibrates it, when every training view has its angle.
  TurnRows turn_rows;
  const bool posed_training = !az.empty() && std::all_of(train.begin(), train.end(), [&](std::size_t r) { return std::isfinite(az[r]); });
  if (posed_training)
    for (auto r : train) turn_rows.group.push_back(detail::captureGroupOf(table.rows[r])), turn_rows.azimuth_deg.push_back(az[r]);
  std::vector<std::string> instances;
  for (auto r : train) instances.push_back(table.rows.at(r).instance);
  for (const OpenSet& s :
       calibrateOpenSets(xtrain, compact, categories, params, options, posed_training ? &turn_rows : nullptr, nullptr,
                         &instances)) {
    OpenSetFoldOutcome o;
    o.method = s.method;
    o.threshold = s.threshold;
    o.known_scores = openSetScores(s, xknown, pknown);
    o.unknown_scores = openSetScores(s, xunknown, punknown);
    for (std::size_t k = 0; k < o.known_scores.size(); ++k)
      if (s.answerFor(o.known_scores[k]) == Answer::Class) ++o.known_accepted, o.known_correct += right[k];
    for (double u : o.unknown_scores) o.unknown_accepted += s.answerFor(u) == Answer::Class;
    for (const auto& seq : known_turns) {
      const int c = fusedClass(known, seq, s, &o.known_scores);
      o.fused_known_correct += c >= 0 && present[static_cast<std::size_t>(c)] == truthOf(seq);
    }
    for (const auto& seq : unknown_turns) o.fused_unknown_accepted += fusedClass(unknown, seq, s, &o.unknown_scores) >= 0;
    out.open_set.push_back(std::move(o));
  }
  return out;
}

std::vector<OpenSetSummary> summariseOpenSet(const std::vector<FoldOutcome>& folds) {
  std::vector<OpenSetSummary> out;
  std::vector<std::vector<double>> aurocs;
  std::vector<std::size_t> accepted_unknown, accepted_known, correct_open, correct_closed;
  std::vector<std::size_t> fused_accepted_unknown, fused_correct_open, fused_correct_closed;
  for (const auto& f : folds)
    for (std::size_t m = 0; m < f.open_set.size(); ++m) {
      const OpenSetFoldOutcome& o = f.open_set[m];
      if (m >= out.size()) {
        out.emplace_back().method = o.method;
        aurocs.emplace_back();
        accepted_unknown.push_back(0), accepted_known.push_back(0), correct_open.push_back(0), correct_closed.push_back(0);
        fused_accepted_unknown.push_back(0), fused_correct_open.push_back(0), fused_correct_closed.push_back(0);
      }
      OpenSetSummary& s = out[m];
      if (s.method != o.method) throw Error("open-set folds list their methods in different orders");
      const double a = auroc(o.known_scores, o.unknown_scores);
      if (std::isfinite(a)) aurocs[m].push_back(a);
      s.false_accept_by_fold.push_back(f.unknown_views ? static_cast<double>(o.unknown_accepted) /
                                                             static_cast<double>(f.unknown_views)
                                                       : std::nan(""));
      s.known_views += f.test_views;
      s.unknown_views += f.unknown_views;
      accepted_unknown[m] += o.unknown_accepted;
      accepted_known[m] += o.known_accepted;
      correct_open[m] += o.known_correct;
      correct_closed[m] += f.correct;
      s.fused_known += f.fused_known;
      s.fused_unknown += f.fused_unknown;
      fused_accepted_unknown[m] += o.fused_unknown_accepted;
      fused_correct_open[m] += o.fused_known_correct;
      fused_correct_closed[m] += f.fused_known_closed_correct;
      s.known_scores.insert(s.known_scores.end(), o.known_scores.begin(), o.known_scores.end());
      s.unknown_scores.insert(s.unknown_scores.end(), o.unknown_scores.begin(), o.unknown_scores.end());
    }
  for (std::size_t m = 0; m < out.size(); ++m) {
    OpenSetSummary& s = out[m];
    double sum = 0, sq = 0;
    for (double a : aurocs[m]) sum += a;
    s.auroc_mean = aurocs[m].empty() ? std::nan("") : sum / static_cast<double>(aurocs[m].size());
    for (double a : aurocs[m]) sq += (a - s.auroc_mean) * (a - s.auroc_mean);
    s.auroc_sd = aurocs[m].size() > 1 ? std::sqrt(sq / static_cast<double>(aurocs[m].size())) : 0.0;
    const double nk = static_cast<double>(std::max<std::size_t>(1, s.known_views));
    s.false_accept = static_cast<double>(accepted_unknown[m]) / static_cast<double>(std::max<std::size_t>(1, s.unknown_views));
    s.known_accuracy_open = static_cast<double>(correct_open[m]) / nk;
    s.known_accuracy_closed = static_cast<double>(correct_closed[m]) / nk;
    s.known_rejected = 1.0 - static_cast<double>(accepted_known[m]) / nk;
    const auto rate = [](std::size_t n, std::size_t of) {
      return of ? static_cast<double>(n) / static_cast<double>(of) : std::nan("");
    };
    s.fused_false_accept = rate(fused_accepted_unknown[m], s.fused_unknown);
    s.fused_known_accuracy_open = rate(fused_correct_open[m], s.fused_known);
    s.fused_known_accuracy_closed = rate(fused_correct_closed[m], s.fused_known);
  }
  return out;
}

}  // namespace keyturn::learning
