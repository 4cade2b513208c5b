#include "keyturn/learning/next_best_view.h"

#include <cmath>
#include <limits>
#include <string>

#include "keyturn/core/error.h"

namespace keyturn::learning {
namespace {

int binOf(double azimuth_deg, double bin_deg, int bins) {
  const long b = std::lround(azimuth_deg / bin_deg);
  return static_cast<int>(((b % bins) + bins) % bins);
}

double circularDistance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

}  // namespace

ViewLikelihoods fitViewLikelihoods(const Matrix& p, const std::vector<int>& truth, const std::vector<double>& az,
                                   int classes, const ViewLikelihoodOptions& o) {
  const auto n = static_cast<std::size_t>(p.rows());
  if (truth.size() != n || az.size() != n || (n > 0 && p.cols() != classes))
    throw Error("view likelihoods: " + std::to_string(n) + " views with " + std::to_string(p.cols()) +
                " probabilities each, " + std::to_string(truth.size()) + " labels, " + std::to_string(az.size()) +
                " azimuths, " + std::to_string(classes) + " classes");
  if (!(o.bin_deg > 0) || 360.0 / o.bin_deg < 4)
    throw Error("view likelihoods: an azimuth bin of " + std::to_string(o.bin_deg) + "° does not divide the turn into 4 or more bins");
  for (int t : truth)
    if (t < 0 || t >= classes) throw Error("view likelihoods: class " + std::to_string(t) + " is not one of " + std::to_string(classes));
  ViewLikelihoods l;
  l.classes = classes;
  l.bins = static_cast<int>(std::lround(360.0 / o.bin_deg));
  const auto C = static_cast<std::size_t>(classes), B = static_cast<std::size_t>(l.bins);
  // Each class's mean over all its views: the fallback of a bin its views do not reach.
  std::vector<std::vector<double>> class_mean(C, std::vector<double>(C, 0.0));
  std::vector<std::size_t> class_views(C, 0);
  for (std::size_t r = 0; r < n; ++r) {
    const auto c = static_cast<std::size_t>(truth[r]);
    ++class_views[c];
    for (std::size_t j = 0; j < C; ++j) class_mean[c][j] += p(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j));
  }
  l.table.assign(C * B * C, 0.0);
  const double half = std::max(o.window_deg, o.bin_deg) / 2;
  for (std::size_t c = 0; c < C; ++c)
    for (std::size_t b = 0; b < B; ++b) {
      std::vector<double> sum(C, 0.0);
      std::size_t m = 0;
      for (std::size_t r = 0; r < n; ++r) {
        if (static_cast<std::size_t>(truth[r]) != c || !std::isfinite(az[r]) ||
            circularDistance(az[r], static_cast<double>(b) * o.bin_deg) > half + 1e-9)
          continue;
        ++m;
        for (std::size_t j = 0; j < C; ++j) sum[j] += p(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j));
      }
      if (m == 0) sum = class_mean[c], m = class_views[c];
      double* cell = &l.table[(c * B + b) * C];
      double total = 0;
      for (std::size_t j = 0; j < C; ++j) {
        const double mean = m ? sum[j] / static_cast<double>(m) : 1.0 / static_cast<double>(C);
        cell[j] = (1 - o.prior) * std::max(0.0, mean) + o.prior / static_cast<double>(C);
        total += cell[j];
      }
      for (std::size_t j = 0; j < C; ++j) cell[j] /= total;
    }
  return l;
}

double entropyOf(const std::vector<double>& p) {
  double h = 0;
  for (double v : p)
    if (v > 0) h -= v * std::log(v);
  return h;
}

double expectedEntropyAfter(const ViewLikelihoods& l, const std::vector<std::vector<double>>& joint, double turn_deg) {
  const auto C = static_cast<std::size_t>(l.classes), B = static_cast<std::size_t>(l.bins);
  if (joint.size() != C || (C > 0 && joint[0].size() != B))
    throw Error("next best view: a belief over " + std::to_string(joint.size()) + " classes and " +
                std::to_string(joint.empty() ? 0 : joint[0].size()) + " rotations against a table of " +
                std::to_string(C) + " classes and " + std::to_string(B) + " bins");
  const int shift = binOf(turn_deg, 360.0 / l.bins, l.bins);
  double top = 0;
  for (const auto& row : joint)
    for (double v : row) top = std::max(top, v);
  // q[c][j] = Σ_φ P(c, φ) L(j | c, φ + δ); rotations with a negligible belief are skipped.
  std::vector<double> q(C * C, 0.0);
  for (std::size_t c = 0; c < C; ++c) {
    if (joint[c].size() != B) throw Error("next best view: the belief's rows differ in length");
    for (std::size_t phi = 0; phi < B; ++phi) {
      const double w = joint[c][phi];
      if (!(w > top * 1e-9)) continue;
      const double* cell = &l.table[(c * B + (phi + static_cast<std::size_t>(shift)) % B) * C];
      for (std::size_t j = 0; j < C; ++j) q[c * C + j] += w * cell[j];
    }
  }
  double expected = 0, total = 0;
  for (std::size_t j = 0; j < C; ++j) {
    double pj = 0;
    for (std::size_t c = 0; c < C; ++c) pj += q[c * C + j];
    if (!(pj > 0)) continue;
    double h = 0;
    for (std::size_t c = 0; c < C; ++c) {
      const double v = q[c * C + j] / pj;
      if (v > 0) h -= v * std::log(v);
    }
    expected += pj * h;
    total += pj;
  }
  return total > 0 ? expected / total : 0.0;
}

NextView chooseNextView(const ViewLikelihoods& l, const std::vector<std::vector<double>>& joint,
                        const std::vector<double>& candidates, const std::vector<double>& taken) {
  const double half_bin = 180.0 / l.bins;
  NextView best;
  best.expected_entropy = std::numeric_limits<double>::infinity();
  bool any = false;
  for (double turn : candidates) {
    bool was_taken = false;
    for (double t : taken) was_taken = was_taken || circularDistance(turn, t) < half_bin;
    if (was_taken) continue;
    const double e = expectedEntropyAfter(l, joint, turn);
    if (!any || e < best.expected_entropy - 1e-12) best = {turn, e};
    any = true;
  }
  if (!any) throw Error("next best view: every one of the " + std::to_string(candidates.size()) + " candidate turns was taken");
  return best;
}

}  // namespace keyturn::learning
