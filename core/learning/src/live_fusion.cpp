#include "keyturn/learning/live_fusion.h"

#include <algorithm>
#include <cmath>

namespace keyturn::learning {

LiveFusion::LiveFusion(const ModelInfo& m, FusionOptions o)
    : classes_(m.classes), references_(m.pose_references), options_(std::move(o)) {
  open_set_.method = m.open_set.method;
  open_set_.threshold = m.open_set.threshold;
  open_set_.turn_threshold = m.open_set.turn_threshold;
  options_.method = references_.empty() ? "independent" : "pose";
  if (!references_.empty()) options_.bin_deg = 360.0 / references_.bins;
  reset();
}

void LiveFusion::reset() {
  taken_.clear();
  turn_ = before_newest_ = TurnFusion(options_, open_set_);
  turned_deg_ = turned_before_newest_ = 0;
}

bool LiveFusion::add(Answer answer, double score, const std::vector<float>& p, const std::vector<float>& features,
                     double az) {
  if (classes_.empty() || answer == Answer::NoObject || !std::isfinite(az) || p.size() != classes_.size()) return false;
  const bool pose = options_.method == "pose";
  if (pose && features.size() != references_.mean.size()) return false;
  const long b = std::lround(az / options_.bin_deg);
  const int bins = static_cast<int>(std::lround(360.0 / options_.bin_deg));
  const int bin = static_cast<int>(((b % bins) + bins) % bins);
  const bool newest = !taken_.empty() && taken_.back().bin == bin;
  if (!newest && std::any_of(taken_.begin(), taken_.end(), [&](const Taken& t) { return t.bin == bin; })) return false;
  if (!newest) {  // the view that was newest is settled: the state before the newest view is all of it
    before_newest_ = turn_;
    turned_before_newest_ = turned_deg_;
    taken_.emplace_back();
  }
  taken_.back() = {bin, az};
  TurnView v{answer, score, p, az, {}};
  if (pose) v.pose = poseEvidence(references_, Eigen::Map<const Eigen::RowVectorXf>(features.data(), static_cast<Eigen::Index>(features.size())));
  // The newest view on the state of the views before it (at rest, a frame costs one view, not the turn).
  turn_ = before_newest_;
  turned_deg_ = turned_before_newest_;
  if (taken_.size() > 1) {
    const double d = std::fmod(std::abs(az - taken_[taken_.size() - 2].azimuth_deg), 360.0);
    turned_deg_ += std::min(d, 360.0 - d);
  }
  turn_.add(v);
  return true;
}

}  // namespace keyturn::learning
