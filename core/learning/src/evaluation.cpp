#include "keyturn/learning/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "keyturn/core/error.h"

namespace keyturn::learning {

double Evaluation::mean() const {
  double s = 0;
  for (const auto& f : folds) s += f.accuracy();
  return folds.empty() ? 0.0 : s / static_cast<double>(folds.size());
}

double Evaluation::stddev() const {
  if (folds.size() < 2) return 0.0;
  const double m = mean();
  double s = 0;
  for (const auto& f : folds) s += (f.accuracy() - m) * (f.accuracy() - m);
  return std::sqrt(s / static_cast<double>(folds.size()));
}

double Evaluation::trainMsPerView() const {
  double ms = 0, n = 0;
  for (const auto& f : folds) ms += f.train_ms, n += static_cast<double>(f.train_views);
  return n ? ms / n : 0.0;
}

double Evaluation::predictMsPerView() const {
  double ms = 0, n = 0;
  for (const auto& f : folds) ms += f.predict_ms, n += static_cast<double>(f.test_views);
  return n ? ms / n : 0.0;
}

FoldOutcome startFoldOutcome(const Fold& fold, const std::vector<std::size_t>& train) {
  FoldOutcome out;
  out.name = fold.name;
  out.train_views = fold.train.size();
  out.twin_views = train.size() - fold.train.size();
  out.test_views = fold.test.size();
  return out;
}

FoldOutcome evaluateFold(const FeatureTable& table, const std::vector<std::string>& blocks,
                         const std::vector<int>& labels, int classes, const Fold& fold,
                         const ClassifierParams& params, const TwinRows& twins) {
  const std::vector<std::size_t> train = withTwins(fold.train, twins);
  FoldOutcome out = startFoldOutcome(fold, train);
  std::vector<int> y;
  for (auto r : train) y.push_back(labels.at(r));
  const auto t0 = std::chrono::steady_clock::now();
  auto clf = makeClassifier(params);
  clf->fit(table.select(blocks, train), y, classes);
  const auto t1 = std::chrono::steady_clock::now();
  const std::vector<int> predicted = argmaxRows(clf->predictProba(table.select(blocks, fold.test)));
  const auto t2 = std::chrono::steady_clock::now();
  out.train_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  out.predict_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();
  std::map<std::pair<int, int>, int> cells;
  for (std::size_t k = 0; k < fold.test.size(); ++k) {
    const int truth = labels[fold.test[k]];
    out.correct += predicted[k] == truth;
    ++cells[{truth, predicted[k]}];
  }
  for (const auto& [tp, n] : cells) out.confusion.push_back({tp.first, tp.second, n});
  return out;
}

std::size_t chooseFeatureSet(const FeatureTable& table, const std::vector<std::string>& candidates,
                             const std::vector<int>& labels, int classes, const std::vector<Fold>& folds,
                             std::size_t fold, int max_inner, const ClassifierParams& params, const TwinRows& twins,
                             std::vector<double>& score) {
  const std::vector<Fold> inner = innerFolds(folds, fold, max_inner);
  if (inner.empty()) throw Error("a choice among feature sets needs a protocol with at least two folds");
  score.clear();
  for (const auto& c : candidates) {
    double sum = 0;
    for (const auto& f : inner) sum += evaluateFold(table, featureSetBlocks(c), labels, classes, f, params, twins).accuracy();
    score.push_back(sum / static_cast<double>(inner.size()));
  }
  return static_cast<std::size_t>(std::max_element(score.begin(), score.end()) - score.begin());
}

FoldOutcome evaluateFoldChoosing(const FeatureTable& table, const std::vector<std::string>& candidates,
                                 const std::vector<int>& labels, int classes, const std::vector<Fold>& folds,
                                 std::size_t fold, int max_inner, const ClassifierParams& params,
                                 const TwinRows& twins) {
  std::vector<double> score;
  const std::size_t best = chooseFeatureSet(table, candidates, labels, classes, folds, fold, max_inner, params, twins, score);
  FoldOutcome out =
      evaluateFold(table, featureSetBlocks(candidates[best]), labels, classes, folds[fold], params, twins);
  out.chosen = candidates[best];
  out.inner_accuracy = std::move(score);
  return out;
}

std::vector<std::vector<int>> sumConfusion(const std::vector<FoldOutcome>& folds, int classes) {
  std::vector<std::vector<int>> m(static_cast<std::size_t>(classes), std::vector<int>(static_cast<std::size_t>(classes), 0));
  for (const auto& f : folds)
    for (const auto& c : f.confusion) m[static_cast<std::size_t>(c.truth)][static_cast<std::size_t>(c.predicted)] += c.count;
  return m;
}

}  // namespace keyturn::learning
