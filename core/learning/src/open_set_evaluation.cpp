#include "keyturn/learning/open_set_evaluation.h"

#include <chrono>
#include <cmath>
#include <map>

#include "keyturn/core/error.h"

namespace keyturn::learning {

FoldOutcome evaluateOpenSetFold(const FeatureTable& table, const std::vector<std::string>& blocks,
                                const std::vector<int>& labels, const Fold& fold, const ClassifierParams& params,
                                const OpenSetOptions& options, const TwinRows& twins) {
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
  for (const OpenSet& s : calibrateOpenSets(xtrain, compact, categories, params, options)) {
    OpenSetFoldOutcome o;
    o.method = s.method;
    o.threshold = s.threshold;
    o.known_scores = openSetScores(s, xknown, pknown);
    o.unknown_scores = openSetScores(s, xunknown, punknown);
    for (std::size_t k = 0; k < o.known_scores.size(); ++k)
      if (s.answerFor(o.known_scores[k]) == Answer::Class) ++o.known_accepted, o.known_correct += right[k];
    for (double u : o.unknown_scores) o.unknown_accepted += s.answerFor(u) == Answer::Class;
    out.open_set.push_back(std::move(o));
  }
  return out;
}

std::vector<OpenSetSummary> summariseOpenSet(const std::vector<FoldOutcome>& folds) {
  std::vector<OpenSetSummary> out;
  std::vector<std::vector<double>> aurocs;
  std::vector<std::size_t> accepted_unknown, accepted_known, correct_open, correct_closed;
  for (const auto& f : folds)
    for (std::size_t m = 0; m < f.open_set.size(); ++m) {
      const OpenSetFoldOutcome& o = f.open_set[m];
      if (m >= out.size()) {
        out.push_back({o.method});
        aurocs.emplace_back();
        accepted_unknown.push_back(0), accepted_known.push_back(0), correct_open.push_back(0), correct_closed.push_back(0);
      }
      OpenSetSummary& s = out[m];
      if (s.method != o.method) throw Error("open-set folds list their methods in different orders");
      const double a = auroc(o.known_scores, o.unknown_scores);
      if (std::isfinite(a)) aurocs[m].push_back(a);
      s.known_views += f.test_views;
      s.unknown_views += f.unknown_views;
      accepted_unknown[m] += o.unknown_accepted;
      accepted_known[m] += o.known_accepted;
      correct_open[m] += o.known_correct;
      correct_closed[m] += f.correct;
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
  }
  return out;
}

}  // namespace keyturn::learning
