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
  refuse();
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
  Taken t;
  t.bin = bin;
  t.unknown = answer == Answer::Unknown;
  t.view.probabilities = p;
  t.view.azimuth_deg = az;
  if (pose) t.view.pose = poseEvidence(references_, Eigen::Map<const Eigen::RowVectorXf>(features.data(), static_cast<Eigen::Index>(features.size())));
  if (newest)
    taken_.back() = std::move(t);
  else
    taken_.push_back(std::move(t));
  refuse();
  return true;
}

// At most one view per bin (72), so building the state again per frame costs little.
void LiveFusion::refuse() {
  state_ = FusionState(options_);
  unknown_ = 0;
  turned_deg_ = 0;
  for (std::size_t i = 0; i < taken_.size(); ++i) {
    const Taken& t = taken_[i];
    if (i > 0) {
      const double d = std::fmod(std::abs(t.view.azimuth_deg - taken_[i - 1].view.azimuth_deg), 360.0);
      turned_deg_ += std::min(d, 360.0 - d);
    }
    unknown_ += t.unknown;
    if (!(t.unknown && open_set_)) state_.add(t.view, state_.views());  // an open-set "unknown" adds no evidence
  }
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
