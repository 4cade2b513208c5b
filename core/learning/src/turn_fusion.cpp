#include "keyturn/learning/turn_fusion.h"

#include <algorithm>
#include <cmath>

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

}  // namespace keyturn::learning
