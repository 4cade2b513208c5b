#include "keyturn/learning/view_fusion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "keyturn/core/error.h"
#include "keyturn/core/median.h"
#include "standardised_views.h"

namespace keyturn::learning {
namespace {

int binOf(double azimuth_deg, double bin_deg, int bins) {
  const long b = std::lround(azimuth_deg / bin_deg);
  return static_cast<int>(((b % bins) + bins) % bins);
}

// Log of a probability, floored so that one view cannot rule a class out alone.
double flooredLog(float p, double floor) { return std::log(std::max(static_cast<double>(p), floor)); }

std::vector<double> normalised(const std::vector<double>& score) {
  const double top = *std::max_element(score.begin(), score.end());
  std::vector<double> b(score.size(), 0.0);
  if (!std::isfinite(top)) {  // every class ruled out: nothing to prefer
    std::fill(b.begin(), b.end(), 1.0 / static_cast<double>(b.size()));
    return b;
  }
  double sum = 0;
  for (std::size_t c = 0; c < score.size(); ++c) sum += b[c] = std::exp(score[c] - top);
  for (double& v : b) v /= sum;
  return b;
}

}  // namespace

const std::vector<std::string>& fusionMethods() {
  static const std::vector<std::string> methods = {"independent", "pose"};
  return methods;
}

void checkFusionMethod(const std::string& method) {
  const auto& m = fusionMethods();
  if (std::find(m.begin(), m.end(), method) == m.end())
    throw Error("fusion method '" + method + "' is not one of independent, pose");
}

PoseReferences fitPoseReferences(const Matrix& x, const std::vector<int>& y, const std::vector<double>& azimuth_deg,
                                 const std::vector<std::string>& group, int classes, double bin_deg) {
  const auto n = static_cast<std::size_t>(x.rows());
  if (y.size() != n || azimuth_deg.size() != n || group.size() != n)
    throw Error("pose references: " + std::to_string(n) + " training views but " + std::to_string(y.size()) +
                " labels, " + std::to_string(azimuth_deg.size()) + " azimuths and " + std::to_string(group.size()) +
                " groups");
  if (!(bin_deg > 0) || 360.0 / bin_deg < 4)
    throw Error("pose fusion's azimuth bin of " + std::to_string(bin_deg) + "° does not divide the turn into 4 or more bins");
  PoseReferences r;
  r.classes = classes;
  r.bins = static_cast<int>(std::lround(360.0 / bin_deg));
  detail::fitStandardisation(x, r.mean, r.scale);
  r.references = detail::standardisedRows(x, r.mean, r.scale);
  r.reference_class = y;
  for (double a : azimuth_deg) r.reference_bin.push_back(binOf(a, bin_deg, r.bins));
  // sigma: how far a training view lies from its class seen another way (another instance or
  // elevation) at the same angle — the spread a test view of a known class shows.
  std::vector<double> across, within;
  for (std::size_t i = 0; i < n; ++i) {
    double best_across = std::numeric_limits<double>::infinity(), best_within = best_across;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || y[j] != y[i]) continue;
      const double d = detail::rmsDistance(r.references.row(static_cast<Eigen::Index>(i)), r.references.row(static_cast<Eigen::Index>(j)));
      best_within = std::min(best_within, d);
      if (group[j] != group[i] && r.reference_bin[j] == r.reference_bin[i]) best_across = std::min(best_across, d);
    }
    if (std::isfinite(best_across)) across.push_back(best_across);
    if (std::isfinite(best_within)) within.push_back(best_within);
  }
  const double s = !across.empty() ? upperMedian(across) : upperMedian(within);
  r.sigma = std::isfinite(s) && s > 1e-9 ? s : 1.0;
  return r;
}

Matrix poseEvidence(const PoseReferences& r, const Eigen::RowVectorXf& x) {
  if (x.size() != static_cast<Eigen::Index>(r.mean.size()))
    throw Error("pose evidence: the references have " + std::to_string(r.mean.size()) + " features, the view " +
                std::to_string(x.size()));
  const Eigen::RowVectorXf v = detail::standardisedRow(x, r.mean, r.scale);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> nearest(static_cast<std::size_t>(r.classes), std::vector<double>(static_cast<std::size_t>(r.bins), inf));
  for (Eigen::Index i = 0; i < r.references.rows(); ++i) {
    const auto c = static_cast<std::size_t>(r.reference_class[static_cast<std::size_t>(i)]);
    auto& d = nearest[c][static_cast<std::size_t>(r.reference_bin[static_cast<std::size_t>(i)])];
    d = std::min(d, detail::rmsDistance(v, r.references.row(i)));
  }
  Matrix e(r.classes, r.bins);
  const double two_s2 = 2 * r.sigma * r.sigma;
  for (int c = 0; c < r.classes; ++c) {
    const auto& row = nearest[static_cast<std::size_t>(c)];
    for (int b = 0; b < r.bins; ++b) {
      double d = inf;  // the bin, or its circularly nearest non-empty neighbour
      for (int off = 0; off <= r.bins / 2 && !std::isfinite(d); ++off)
        d = std::min(row[static_cast<std::size_t>((b + off) % r.bins)], row[static_cast<std::size_t>((b - off + r.bins) % r.bins)]);
      e(c, b) = std::isfinite(d) ? static_cast<float>(-d * d / two_s2) : -std::numeric_limits<float>::infinity();
    }
  }
  return e;
}

FusionState::FusionState(const FusionOptions& o) : options_(o), pose_(o.method == "pose") { checkFusionMethod(o.method); }

void FusionState::add(const FusionView& v, std::size_t index) {
  const std::string which = "fusion: view " + std::to_string(index + 1);
  if (views_ == 0) {
    if (v.probabilities.empty()) throw Error("fusion: the first view has no class probabilities");
    evidence_.assign(v.probabilities.size(), 0.0);
    if (pose_) {
      if (v.pose.rows() != static_cast<Eigen::Index>(evidence_.size()) || v.pose.cols() < 4)
        throw Error(which + " has no pose evidence for its " + std::to_string(evidence_.size()) + " classes");
      bins_ = static_cast<int>(v.pose.cols());
      aligned_.assign(evidence_.size(), std::vector<double>(static_cast<std::size_t>(bins_), 0.0));
    }
  }
  const std::size_t classes = evidence_.size();
  if (v.probabilities.size() != classes)
    throw Error(which + " has " + std::to_string(v.probabilities.size()) + " class probabilities, the first " +
                std::to_string(classes));
  if (pose_ && (v.pose.rows() != static_cast<Eigen::Index>(classes) || v.pose.cols() != bins_))
    throw Error(which + " has no pose evidence for its " + std::to_string(classes) + " classes");
  if (!std::isfinite(v.azimuth_deg)) throw Error(which + " has no azimuth");
  if (views_ == 0) first_azimuth_ = v.azimuth_deg;
  for (std::size_t c = 0; c < classes; ++c) evidence_[c] += flooredLog(v.probabilities[c], options_.probability_floor);
  if (pose_) {
    const int shift = binOf(v.azimuth_deg - first_azimuth_, 360.0 / bins_, bins_);
    for (std::size_t c = 0; c < classes; ++c)
      for (int phi = 0; phi < bins_; ++phi)
        aligned_[c][static_cast<std::size_t>(phi)] += v.pose(static_cast<Eigen::Index>(c), (phi + shift) % bins_);
  }
  ++views_;
}

std::vector<double> FusionState::belief() const {
  std::vector<double> score = evidence_;
  if (pose_)
    for (std::size_t c = 0; c < score.size(); ++c)
      score[c] += *std::max_element(aligned_[c].begin(), aligned_[c].end());
  return normalised(score);
}

std::vector<std::vector<double>> FusionState::jointBelief() const {
  if (!pose_) throw Error("fusion: the belief over classes and rotations needs pose fusion, not " + options_.method);
  if (views_ == 0) throw Error("fusion: no view yet, so no belief over classes and rotations");
  std::vector<double> flat;
  for (std::size_t c = 0; c < evidence_.size(); ++c)
    for (double a : aligned_[c]) flat.push_back(evidence_[c] + a);
  flat = normalised(flat);
  std::vector<std::vector<double>> joint(evidence_.size());
  for (std::size_t c = 0; c < evidence_.size(); ++c)
    joint[c].assign(flat.begin() + static_cast<std::ptrdiff_t>(c * static_cast<std::size_t>(bins_)),
                    flat.begin() + static_cast<std::ptrdiff_t>((c + 1) * static_cast<std::size_t>(bins_)));
  return joint;
}

FusedSequence fuseViews(const std::vector<FusionView>& views, const FusionOptions& o) {
  checkFusionMethod(o.method);
  if (views.empty()) throw Error("fusion: a sequence needs at least one view");
  FusionState state(o);
  FusedSequence out;
  for (std::size_t i = 0; i < views.size(); ++i) {
    state.add(views[i], i);
    out.belief.push_back(state.belief());
    const auto& b = out.belief.back();
    out.best.push_back(static_cast<int>(std::max_element(b.begin(), b.end()) - b.begin()));
    if (out.stopped_after == 0 && b[static_cast<std::size_t>(out.best.back())] >= o.stop_belief) out.stopped_after = i + 1;
  }
  if (out.stopped_after == 0) out.stopped_after = views.size();
  return out;
}

}  // namespace keyturn::learning
