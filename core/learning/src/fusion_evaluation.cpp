#include "keyturn/learning/fusion_evaluation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <random>

#include "keyturn/core/error.h"
#include "keyturn/core/parallel_for.h"
#include "fold_views.h"

namespace keyturn::learning {

std::vector<double> FusionSchedule::offsets(int views) const {
  std::vector<double> o;
  for (int i = 0; i < views; ++i)
    o.push_back(spread_deg > 0 ? (views > 1 ? spread_deg * i / (views - 1) : 0.0) : step_deg * i);
  return o;
}

FusionSchedule parseFusionSchedule(const std::string& text) {
  const bool step = text.rfind("step", 0) == 0;
  const std::string number = step ? text.substr(4) : text;
  char* end = nullptr;
  const double deg = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !(deg > 0) || deg >= 360)
    throw Error("fusion schedule '" + text + "' is not DEGREES (views spread over them) or stepDEGREES, 0 < DEGREES < 360");
  FusionSchedule s;
  char name[64];
  std::snprintf(name, sizeof name, step ? "step %g°" : "over %g°", deg);
  s.name = name;
  (step ? s.step_deg : s.spread_deg) = deg;
  return s;
}

double FusionCurve::accuracy(std::size_t n) const {
  return n >= 1 && n <= sequences.size() && sequences[n - 1] ? static_cast<double>(correct[n - 1]) / static_cast<double>(sequences[n - 1]) : std::nan("");
}

double FusionCurve::meanTrueBelief(std::size_t n) const {
  return n >= 1 && n <= sequences.size() && sequences[n - 1] ? true_belief[n - 1] / static_cast<double>(sequences[n - 1]) : std::nan("");
}

namespace {

struct Tally {
  std::vector<std::size_t> sequences, correct;
  std::vector<double> belief;
};

}  // namespace

FusionProtocolResult evaluateFusion(const FeatureTable& t, const std::vector<double>& az,
                                    const std::vector<std::string>& blocks, const std::string& protocol,
                                    const ClassifierParams& params, const FusionEvaluationOptions& o, int jobs) {
  if (protocol != "leave-instance" && protocol != "leave-elevation")
    throw Error("the fusion protocol runs over leave-instance or leave-elevation folds, not '" + protocol + "'");
  if (az.size() != t.rows.size())
    throw Error("fusion: " + std::to_string(t.rows.size()) + " views but " + std::to_string(az.size()) + " azimuths");
  if (o.schedules.empty() || o.max_views < 1) throw Error("fusion: no schedule or no views to fuse");
  for (const auto& m : o.methods) checkFusionMethod(m);
  const Protocol proto = makeProtocol(protocol, t, 7);
  if (proto.folds.empty()) throw Error("fusion: " + protocol + " has no folds on this dataset");
  FusionProtocolResult res;
  res.protocol = protocol;
  res.label_kind = proto.labels.kindName();
  res.folds = proto.folds.size();
  const std::size_t methods = o.methods.size(), schedules = o.schedules.size();
  const auto n_max = static_cast<std::size_t>(o.max_views);
  // tallies[schedule][method][shuffled]
  const Tally zero{std::vector<std::size_t>(n_max, 0), std::vector<std::size_t>(n_max, 0), std::vector<double>(n_max, 0.0)};
  std::vector<Tally> tallies(schedules * methods * 2, zero);
  std::vector<FusionStopping> stopping(methods);
  std::mutex lock;
  parallelFor(proto.folds.size(), jobs, [&](std::size_t f) {
    ClassifierParams p = params;
    p.xgboost.threads = 1;  // folds train in parallel; one thread each keeps a fold's model the same on any machine
    const detail::TrainedFold trained = detail::trainFold(t, az, blocks, proto.labels, proto.folds[f], p, o.fusion.bin_deg);
    const detail::FoldViews fv = detail::predictTestViews(trained, t, az, blocks, proto.labels, proto.folds[f]);
    const detail::GroupedViews groups = detail::groupsByAngle(fv.views, fv.group);
    std::vector<Tally> local(tallies.size(), zero);
    std::vector<FusionStopping> local_stop(methods);
    std::mt19937_64 rng(o.seed + f);
    for (const auto& [name, members] : groups)
      for (const auto& [start_az, start] : members)
        for (std::size_t s = 0; s < schedules; ++s)
          for (int n = 1; n <= o.max_views; ++n) {
            std::vector<FusionView> seq;
            for (int i : detail::viewsAtOffsets(members, start_az, o.schedules[s].offsets(n), o.tolerance_deg))
              seq.push_back(fv.views[static_cast<std::size_t>(i)]);
            if (seq.size() != static_cast<std::size_t>(n)) continue;
            const int truth = fv.truth[static_cast<std::size_t>(start)];
            // The control: the same views, their poses dealt out in another order.
            std::vector<FusionView> shuffled = seq;
            if (n > 1) {
              std::vector<double> poses;
              for (const auto& v : seq) poses.push_back(v.azimuth_deg);
              std::vector<double> dealt = poses;
              while (dealt == poses) std::shuffle(dealt.begin(), dealt.end(), rng);
              for (int i = 0; i < n; ++i) shuffled[static_cast<std::size_t>(i)].azimuth_deg = dealt[static_cast<std::size_t>(i)];
            }
            for (std::size_t m = 0; m < methods; ++m) {
              FusionOptions fo = o.fusion;
              fo.method = o.methods[m];
              for (int sh = 0; sh < 2; ++sh) {
                const FusedSequence fs = fuseViews(sh ? shuffled : seq, fo);
                Tally& tl = local[(s * methods + m) * 2 + static_cast<std::size_t>(sh)];
                const auto k = static_cast<std::size_t>(n - 1);
                ++tl.sequences[k];
                tl.correct[k] += fs.best.back() == truth;
                tl.belief[k] += fs.belief.back()[static_cast<std::size_t>(truth)];
                if (s == 0 && sh == 0 && n == o.max_views) {
                  auto& st = local_stop[m];
                  ++st.sequences;
                  st.views += fs.stopped_after;
                  st.correct += fs.best[fs.stopped_after - 1] == truth;
                }
              }
            }
          }
    std::lock_guard<std::mutex> g(lock);
    res.test_views += fv.views.size();
    res.single_view_correct += fv.single_correct;
    for (std::size_t k = 0; k < tallies.size(); ++k)
      for (std::size_t n = 0; n < n_max; ++n) {
        tallies[k].sequences[n] += local[k].sequences[n];
        tallies[k].correct[n] += local[k].correct[n];
        tallies[k].belief[n] += local[k].belief[n];
      }
    for (std::size_t m = 0; m < methods; ++m) {
      stopping[m].sequences += local_stop[m].sequences;
      stopping[m].correct += local_stop[m].correct;
      stopping[m].views += local_stop[m].views;
    }
  });
  for (std::size_t s = 0; s < schedules; ++s)
    for (std::size_t m = 0; m < methods; ++m)
      for (int sh = 0; sh < 2; ++sh) {
        const Tally& tl = tallies[(s * methods + m) * 2 + static_cast<std::size_t>(sh)];
        res.curves.push_back({o.schedules[s].name, o.methods[m], sh == 1, tl.sequences, tl.correct, tl.belief});
      }
  for (std::size_t m = 0; m < methods; ++m) stopping[m].method = o.methods[m];
  res.stopping = stopping;
  return res;
}

}  // namespace keyturn::learning
