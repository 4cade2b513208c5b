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
  state_ = FusionState(options_);
  bins_.clear();
  unknown_ = 0;
  turned_deg_ = 0;
}

bool LiveFusion::add(Answer answer, const std::vector<float>& p, const std::vector<float>& features, double az) {
  if (classes_.empty() || answer == Answer::NoObject || !std::isfinite(az) || p.size() != classes_.size()) return false;
  const long b = std::lround(az / options_.bin_deg);
  const int bins = static_cast<int>(std::lround(360.0 / options_.bin_deg));
  const int bin = static_cast<int>(((b % bins) + bins) % bins);
  if (std::find(bins_.begin(), bins_.end(), bin) != bins_.end()) return false;
  const bool pose = options_.method == "pose";
  if (pose && features.size() != references_.mean.size()) return false;
  if (!bins_.empty()) {
    const double d = std::fmod(std::abs(az - last_deg_), 360.0);
    turned_deg_ += std::min(d, 360.0 - d);
  }
  last_deg_ = az;
  bins_.push_back(bin);
  if (answer == Answer::Unknown && open_set_) {
    ++unknown_;
    return true;
  }
  if (answer == Answer::Unknown) ++unknown_;
  FusionView v;
  v.probabilities = p;
  v.azimuth_deg = az;
  if (pose) v.pose = poseEvidence(references_, Eigen::Map<const Eigen::RowVectorXf>(features.data(), static_cast<Eigen::Index>(features.size())));
  state_.add(v, state_.views());
  return true;
}

std::vector<double> LiveFusion::belief() const { return state_.views() ? state_.belief() : std::vector<double>(); }

int LiveFusion::best() const {
  const auto b = belief();
  return b.empty() ? -1 : static_cast<int>(std::max_element(b.begin(), b.end()) - b.begin());
}

Answer LiveFusion::answer() const {
  if (state_.views() == 0) return unknown_ ? Answer::Unknown : Answer::NoObject;
  return open_set_ && 2 * unknown_ >= bins_.size() ? Answer::Unknown : Answer::Class;
}

}  // namespace keyturn::learning
