#include "keyturn/learning/live_fusion.h"

#include <algorithm>
#include <cmath>

namespace keyturn::learning {

LiveFusion::LiveFusion(const ModelInfo& m, FusionOptions o)
    : classes_(m.classes), references_(m.pose_references), open_set_(m.open_set.enabled()), options_(std::move(o)) {
  options_.method = references_.empty() ? "independent" : "pose";
  if (!references_.empty()) options_.bin_deg = 360.0 / references_.bins;
  reset();
}

void LiveFusion::reset() {
  taken_.clear();
  state_ = before_newest_ = FusionState(options_);
  unknown_ = unknown_before_newest_ = 0;
  turned_deg_ = turned_before_newest_ = 0;
}

bool LiveFusion::add(Answer answer, const std::vector<float>& p, const std::vector<float>& features, double az) {
  if (classes_.empty() || answer == Answer::NoObject || !std::isfinite(az) || p.size() != classes_.size()) return false;
  const bool pose = options_.method == "pose";
  if (pose && features.size() != references_.mean.size()) return false;
  const long b = std::lround(az / options_.bin_deg);
  const int bins = static_cast<int>(std::lround(360.0 / options_.bin_deg));
  const int bin = static_cast<int>(((b % bins) + bins) % bins);
  const bool newest = !taken_.empty() && taken_.back().bin == bin;
  if (!newest && std::any_of(taken_.begin(), taken_.end(), [&](const Taken& t) { return t.bin == bin; })) return false;
  if (!newest) {  // the view that was newest is settled: the state before the newest view is all of it
    before_newest_ = state_;
    unknown_before_newest_ = unknown_;
    turned_before_newest_ = turned_deg_;
    taken_.emplace_back();
  }
  taken_.back() = {bin, az};
  FusionView v;
  v.probabilities = p;
  v.azimuth_deg = az;
  if (pose) v.pose = poseEvidence(references_, Eigen::Map<const Eigen::RowVectorXf>(features.data(), static_cast<Eigen::Index>(features.size())));
  // The newest view on the state of the views before it (at rest, a frame costs one view, not the turn).
  const bool unknown = answer == Answer::Unknown;
  state_ = before_newest_;
  unknown_ = unknown_before_newest_ + unknown;
  turned_deg_ = turned_before_newest_;
  if (taken_.size() > 1) {
    const double d = std::fmod(std::abs(az - taken_[taken_.size() - 2].azimuth_deg), 360.0);
    turned_deg_ += std::min(d, 360.0 - d);
  }
  if (!(unknown && open_set_)) state_.add(v, state_.views());  // an open-set "unknown" adds no evidence
  return true;
}

std::vector<double> LiveFusion::belief() const { return state_.views() ? state_.belief() : std::vector<double>(); }

int LiveFusion::best() const {
  const auto b = belief();
  return b.empty() ? -1 : static_cast<int>(std::max_element(b.begin(), b.end()) - b.begin());
}

Answer LiveFusion::answer() const {
  if (state_.views() == 0) return unknown_ ? Answer::Unknown : Answer::NoObject;
  return open_set_ && fusedAnswerIsUnknown(unknown_, taken_.size()) ? Answer::Unknown : Answer::Class;
}

}  // namespace keyturn::learning
