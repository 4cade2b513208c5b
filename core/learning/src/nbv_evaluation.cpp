#include "keyturn/learning/nbv_evaluation.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "keyturn/core/error.h"
#include "keyturn/core/parallel_for.h"
#include "fold_views.h"

namespace keyturn::learning {

double ViewCountCurve::accuracy(std::size_t n) const {
  return n >= 1 && n <= sequences.size() && sequences[n - 1]
             ? static_cast<double>(correct[n - 1]) / static_cast<double>(sequences[n - 1])
             : std::nan("");
}

double StoppingPoint::accuracy() const {
  return sequences ? static_cast<double>(correct) / static_cast<double>(sequences) : std::nan("");
}

double StoppingPoint::meanViews() const {
  return sequences ? static_cast<double>(views) / static_cast<double>(sequences) : std::nan("");
}

double NbvProtocolResult::target() const {
  for (const auto& c : curves)
    if (c.policy != kNextBestViewPolicy) return c.accuracy(static_cast<std::size_t>(target_views));
  return std::nan("");
}

double viewsToReach(const NbvProtocolResult& r, const std::string& policy, double accuracy) {
  double best = std::nan("");
  for (const auto& s : r.stopping)
    if (s.policy == policy && s.accuracy() >= accuracy - 1e-12 && !(s.meanViews() >= best)) best = s.meanViews();
  return best;
}

namespace {

// One fold's test views as fusion sees them, and the classifier's per-angle behaviour.
struct FoldData : detail::FoldViews {
  ViewLikelihoods likelihoods;
};

// Held-out class probabilities of the training rows `train` (indices into t): the protocol run
// inside them; the rows of a class no inner fold tests take `in_sample`'s.
Matrix heldOutProbabilities(const FeatureTable& t, const std::vector<std::size_t>& train, const std::vector<int>& y,
                            const std::vector<std::string>& blocks, const std::string& protocol,
                            const ClassifierParams& params, int classes, const Matrix& in_sample,
                            std::vector<int>& truth, std::vector<std::size_t>& rows) {
  FeatureTable sub;
  sub.blocks = t.blocks;
  sub.sizes = t.sizes;
  sub.spec = t.spec;
  for (auto r : train) sub.rows.push_back(t.rows[r]);
  Protocol inner;
  try {
    inner = makeProtocol(protocol, sub, 7);
  } catch (const Error&) {
    inner.folds.clear();  // too few groups inside the training views: in-sample only
  }
  std::vector<Eigen::RowVectorXf> out;
  std::vector<bool> held(static_cast<std::size_t>(classes), false);
  for (const Fold& f : inner.folds) {
    if (f.train.empty() || f.test.empty()) continue;
    std::vector<int> fy;
    for (auto k : f.train) fy.push_back(y[k]);
    std::vector<std::size_t> ftrain, ftest;
    for (auto k : f.train) ftrain.push_back(train[k]);
    for (auto k : f.test) ftest.push_back(train[k]);
    auto clf = makeClassifier(params);
    clf->fit(t.select(blocks, ftrain), fy, classes);
    const Matrix p = clf->predictProba(t.select(blocks, ftest));
    for (std::size_t i = 0; i < f.test.size(); ++i) {
      out.push_back(p.row(static_cast<Eigen::Index>(i)));
      truth.push_back(y[f.test[i]]);
      rows.push_back(f.test[i]);
      held[static_cast<std::size_t>(y[f.test[i]])] = true;
    }
  }
  for (std::size_t k = 0; k < train.size(); ++k)
    if (!held[static_cast<std::size_t>(y[k])]) {
      out.push_back(in_sample.row(static_cast<Eigen::Index>(k)));
      truth.push_back(y[k]);
      rows.push_back(k);
    }
  Matrix m(static_cast<Eigen::Index>(out.size()), classes);
  for (std::size_t i = 0; i < out.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = out[i];
  return m;
}

FoldData prepareFold(const FeatureTable& t, const std::vector<double>& az, const std::vector<std::string>& blocks,
                     const std::string& protocol, const Labels& labels, const Fold& fold, const ClassifierParams& params,
                     const NbvEvaluationOptions& o) {
  const int classes = static_cast<int>(labels.names.size());
  const detail::TrainedFold trained = detail::trainFold(t, az, blocks, labels, fold, params, o.fusion.bin_deg);
  FoldData out;
  static_cast<detail::FoldViews&>(out) = detail::predictTestViews(trained, t, az, blocks, labels, fold);
  std::vector<int> truth;
  std::vector<std::size_t> rows;
  const Matrix held = heldOutProbabilities(t, trained.train, trained.y, blocks, protocol, params, classes,
                                           trained.classifier->predictProba(trained.x), truth, rows);
  std::vector<double> held_az;
  for (auto k : rows) held_az.push_back(trained.azimuth_deg[k]);
  ViewLikelihoodOptions lo;
  lo.bin_deg = o.fusion.bin_deg;
  lo.window_deg = o.likelihood_window_deg;
  out.likelihoods = fitViewLikelihoods(held, truth, held_az, classes, lo);
  return out;
}

// Tallies of one fold (or all): per policy, the curve and the stopping points.
struct Tally {
  std::vector<ViewCountCurve> curves;
  std::vector<StoppingPoint> stopping;
  std::map<int, std::size_t> first_turns;
};

Tally emptyTally(const NbvEvaluationOptions& o) {
  Tally t;
  std::vector<std::string> policies = {kNextBestViewPolicy};
  for (const auto& s : o.fixed) policies.push_back(s.name);
  const auto n = static_cast<std::size_t>(o.max_views);
  for (const auto& p : policies) {
    t.curves.push_back({p, std::vector<std::size_t>(n, 0), std::vector<std::size_t>(n, 0)});
    for (double b : o.stop_beliefs) t.stopping.push_back({p, b, 0, 0, 0});
  }
  return t;
}

// One sequence's beliefs after each view, tallied for policy index `k`.
void tallySequence(Tally& t, std::size_t k, const std::vector<std::vector<double>>& beliefs, int truth,
                   const NbvEvaluationOptions& o) {
  auto& c = t.curves[k];
  std::vector<int> best;
  std::vector<double> top;
  for (std::size_t n = 0; n < beliefs.size(); ++n) {
    const auto& b = beliefs[n];
    const auto it = std::max_element(b.begin(), b.end());
    best.push_back(static_cast<int>(it - b.begin()));
    top.push_back(*it);
    ++c.sequences[n];
    c.correct[n] += best.back() == truth;
  }
  for (std::size_t s = 0; s < o.stop_beliefs.size(); ++s) {
    std::size_t n = 0;
    while (n + 1 < beliefs.size() && top[n] < o.stop_beliefs[s]) ++n;
    auto& p = t.stopping[k * o.stop_beliefs.size() + s];
    ++p.sequences;
    p.views += n + 1;
    p.correct += best[n] == truth;
  }
}

}  // namespace

NbvProtocolResult evaluateNextBestView(const FeatureTable& t, const std::vector<double>& az,
                                       const std::vector<std::string>& blocks, const std::string& protocol,
                                       const ClassifierParams& params, const NbvEvaluationOptions& o, int jobs) {
  if (protocol != "leave-instance" && protocol != "leave-elevation")
    throw Error("the next-best-view protocol runs over leave-instance or leave-elevation folds, not '" + protocol + "'");
  if (az.size() != t.rows.size())
    throw Error("next best view: " + std::to_string(t.rows.size()) + " views but " + std::to_string(az.size()) + " azimuths");
  if (o.fixed.empty()) throw Error("next best view: no fixed schedule to compare with");
  if (o.max_views < 2) throw Error("next best view: sequences of " + std::to_string(o.max_views) + " views choose none");
  if (o.target_views < 1 || o.target_views > o.max_views)
    throw Error("next best view: the target after " + std::to_string(o.target_views) + " views is not within 1 … " +
                std::to_string(o.max_views));
  if (!(o.candidate_step_deg > 0) || o.candidate_step_deg >= 180)
    throw Error("next best view: a candidate step of " + std::to_string(o.candidate_step_deg) + "° is not within (0, 180)");
  FusionOptions fusion = o.fusion;
  fusion.method = "pose";
  const Protocol proto = makeProtocol(protocol, t, 7);
  if (proto.folds.empty()) throw Error("next best view: " + protocol + " has no folds on this dataset");
  std::vector<double> candidates;
  for (double d = o.candidate_step_deg; d < 360 - 1e-9; d += o.candidate_step_deg) candidates.push_back(d);

  NbvProtocolResult res;
  res.protocol = protocol;
  res.label_kind = proto.labels.kindName();
  res.folds = proto.folds.size();
  res.target_views = o.target_views;
  Tally total = emptyTally(o);
  std::mutex lock;
  parallelFor(proto.folds.size(), jobs, [&](std::size_t f) {
    ClassifierParams p = params;
    p.xgboost.threads = 1;  // folds train in parallel; one thread each keeps a fold's model the same on any machine
    const FoldData fd = prepareFold(t, az, blocks, protocol, proto.labels, proto.folds[f], p, o);
    detail::GroupedViews groups = detail::groupsByAngle(fd.views, fd.group);
    Tally local = emptyTally(o);
    for (auto& [name, members] : groups) {
      std::sort(members.begin(), members.end());
      for (std::size_t s = 0; s < members.size(); s += static_cast<std::size_t>(std::max(1, o.start_every))) {
        const auto [start_az, start] = members[s];
        const int truth = fd.truth[static_cast<std::size_t>(start)];
        // Next best view: after each view, the reachable turn with the lowest expected entropy.
        std::vector<double> reachable;
        for (double d : candidates)
          if (detail::viewAt(members, start_az + d, o.tolerance_deg) >= 0) reachable.push_back(d);
        FusionState nbv(fusion);
        nbv.add(fd.views[static_cast<std::size_t>(start)], 0);
        std::vector<std::vector<double>> beliefs = {nbv.belief()};
        std::vector<double> taken = {0.0};
        while (static_cast<int>(beliefs.size()) < o.max_views && taken.size() <= reachable.size()) {
          const NextView next = chooseNextView(fd.likelihoods, nbv.jointBelief(), reachable, taken);
          if (taken.size() == 1) ++local.first_turns[static_cast<int>(std::lround(next.turn_deg))];
          taken.push_back(next.turn_deg);
          nbv.add(fd.views[static_cast<std::size_t>(detail::viewAt(members, start_az + next.turn_deg, o.tolerance_deg))],
                  beliefs.size());
          beliefs.push_back(nbv.belief());
        }
        if (static_cast<int>(beliefs.size()) == o.max_views) tallySequence(local, 0, beliefs, truth, o);
        // The fixed steps, fused the same way.
        for (std::size_t k = 0; k < o.fixed.size(); ++k) {
          FusionState fixed(fusion);
          std::vector<std::vector<double>> fb;
          for (int i : detail::viewsAtOffsets(members, start_az, o.fixed[k].offsets(o.max_views), o.tolerance_deg)) {
            fixed.add(fd.views[static_cast<std::size_t>(i)], fb.size());
            fb.push_back(fixed.belief());
          }
          if (static_cast<int>(fb.size()) == o.max_views) tallySequence(local, k + 1, fb, truth, o);
        }
      }
    }
    std::lock_guard<std::mutex> g(lock);
    res.test_views += fd.views.size();
    res.single_view_correct += fd.single_correct;
    for (std::size_t k = 0; k < total.curves.size(); ++k)
      for (std::size_t n = 0; n < total.curves[k].sequences.size(); ++n) {
        total.curves[k].sequences[n] += local.curves[k].sequences[n];
        total.curves[k].correct[n] += local.curves[k].correct[n];
      }
    for (std::size_t k = 0; k < total.stopping.size(); ++k) {
      total.stopping[k].sequences += local.stopping[k].sequences;
      total.stopping[k].correct += local.stopping[k].correct;
      total.stopping[k].views += local.stopping[k].views;
    }
    for (const auto& [turn, n] : local.first_turns) total.first_turns[turn] += n;
  });
  res.curves = std::move(total.curves);
  res.stopping = std::move(total.stopping);
  res.first_turns = std::move(total.first_turns);
  return res;
}

}  // namespace keyturn::learning
