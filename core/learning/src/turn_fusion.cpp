#include "keyturn/learning/turn_fusion.h"

#include <algorithm>
#include <cmath>

#include "keyturn/learning/fusion_evaluation.h"
#include "fold_views.h"

namespace keyturn::learning {

TurnFusion::TurnFusion(const FusionOptions& o, const OpenSet& s) : options_(o), state_(o) {
  rule_.method = s.method;
  rule_.threshold = s.threshold;
  rule_.turn_threshold = s.turn_threshold;
}

void TurnFusion::add(const TurnView& v) {
  if (v.answer == Answer::NoObject) return;
  const bool unknown = v.answer == Answer::Unknown;
  if (!(unknown && rule_.enabled())) state_.add({v.probabilities, v.azimuth_deg, v.pose}, views_);
  ++views_;
  unknown_ += unknown;
  score_sum_ += std::isfinite(v.score) ? v.score : 0.0;
}

std::vector<double> TurnFusion::belief() const { return state_.views() ? state_.belief() : std::vector<double>(); }

int TurnFusion::best() const {
  const auto b = belief();
  return b.empty() ? -1 : static_cast<int>(std::max_element(b.begin(), b.end()) - b.begin());
}

Answer TurnFusion::answer() const {
  if (views_ == 0) return Answer::NoObject;
  if (state_.views() == 0) return Answer::Unknown;
  if (rule_.enabled() && score_sum_ / static_cast<double>(views_) < rule_.thresholdFor(views_)) return Answer::Unknown;
  return Answer::Class;
}

double TurnFusion::topBelief() const {
  const auto b = belief();
  return b.empty() ? 0.0 : *std::max_element(b.begin(), b.end());
}

bool TurnFusion::certain() const { return answer() == Answer::Class && topBelief() >= options_.stop_belief; }

bool TurnFusion::certainWhileUnknown() const { return answer() == Answer::Unknown && topBelief() >= options_.stop_belief; }

std::vector<std::vector<int>> turnsOf(const std::vector<double>& az, const std::vector<std::string>& group) {
  std::vector<FusionView> views(az.size());
  for (std::size_t i = 0; i < az.size(); ++i) views[i].azimuth_deg = az[i];
  FusionSchedule turn;
  turn.spread_deg = kTurnSpreadDeg;
  const std::vector<double> offsets = turn.offsets(kTurnViews);
  const double tolerance_deg = FusionEvaluationOptions().tolerance_deg;
  std::vector<std::vector<int>> turns;
  for (const auto& [name, members] : detail::groupsByAngle(views, group))
    for (const auto& [start_deg, start] : members) {
      std::vector<int> seq = detail::viewsAtOffsets(members, start_deg, offsets, tolerance_deg);
      if (seq.size() == offsets.size()) turns.push_back(std::move(seq));
    }
  return turns;
}

}  // namespace keyturn::learning
