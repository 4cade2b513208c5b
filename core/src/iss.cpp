#include "keyturn/core/iss.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>

namespace keyturn {
namespace {
constexpr double kPlanarRatio = 1e-9;
// What a filled keypoint weighs against a local maximum's 1 (with a hard budget): enough to steady
// the PDFs, little enough that on a view of few maxima the salient points still shape them. Weight 1
// lost 2.3 points where a small model meets such views; 0.3, the first value tried, lost nowhere
// (docs/descriptors.md, "A budget K always reaches").
constexpr double kFilledWeight = 0.3;

Eigen::Vector3d ascendingEigenvalues(const Eigen::Matrix3d& scatter) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(scatter, Eigen::EigenvaluesOnly);
  return eig.eigenvalues();
}

// ISS's saliency λ3 from the scatter's eigenvalues, 0 where the ratio tests fail.
double saliencyOf(const Eigen::Vector3d& ev, const IssOptions& o) {
  const double l1 = ev[2], l2 = ev[1], l3 = ev[0];
  // A planar or linear patch has λ3 or λ2 = 0 up to float rounding of the
  // coordinates (~1e-11 of λ1): not salient, and no ratio divides by zero.
  if (l1 <= 0.0 || l2 <= kPlanarRatio * l1 || l3 <= kPlanarRatio * l1) return 0.0;
  return l2 / l1 < o.gamma21 && l3 / l2 < o.gamma32 ? l3 : 0.0;
}

// IssOptions::fill_budget: after the local maxima, the other points by saliency (the ratio tests'
// rejects after every salient point, by λ3), each kept when it is at least r from every keypoint;
// r halves until the budget is met. Ties go to the lower index, so the outcome is deterministic.
void fillBudget(const PointSet& set, IssResult& result, const std::vector<double>& lambda3, float r, int budget) {
  const int n = static_cast<int>(set.size());
  std::vector<char> chosen(static_cast<std::size_t>(n), 0);
  for (int i : result.keypoints) chosen[static_cast<std::size_t>(i)] = 1;
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (!chosen[static_cast<std::size_t>(i)]) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const bool sa = result.saliency[a] > 0, sb = result.saliency[b] > 0;
    if (sa != sb) return sa;
    return sa ? result.saliency[a] > result.saliency[b] : lambda3[a] > lambda3[b];
  });
  const std::size_t before = result.keypoints.size();
  for (float radius = r; static_cast<int>(result.keypoints.size()) < budget && radius > 1e-9f; radius *= 0.5f) {
    const float r2 = radius * radius;
    for (int i : order) {
      if (static_cast<int>(result.keypoints.size()) >= budget) break;
      if (chosen[static_cast<std::size_t>(i)]) continue;
      bool far = true;
      for (int k : result.keypoints)
        if ((set.points[k] - set.points[i]).squaredNorm() < r2) {
          far = false;
          break;
        }
      if (!far) continue;
      chosen[static_cast<std::size_t>(i)] = 1;
      result.keypoints.push_back(i);
    }
  }
  result.filled = static_cast<int>(result.keypoints.size() - before);
  std::sort(result.keypoints.begin(), result.keypoints.end());
}
}  // namespace

double issSaliency(const Eigen::Matrix3d& scatter, const IssOptions& o) {
  return saliencyOf(ascendingEigenvalues(scatter), o);
}

IssResult detectIssKeypoints(const PointSet& set, const RadiusSearch& search, double resolution,
                             const IssOptions& o) {
  const int n = static_cast<int>(set.size());
  const float r_density = static_cast<float>(o.density_radius * resolution);
  const float r_frame = static_cast<float>(o.frame_radius * resolution);
  const float r_nms = static_cast<float>(o.nms_radius * resolution);
  std::vector<int> nb;

  // Eq. (8): weight inversely proportional to the local density.
  std::vector<double> weight(n);
  for (int i = 0; i < n; ++i) {
    search.radius(i, r_density, nb);
    weight[i] = 1.0 / static_cast<double>(nb.size());  // nb holds i itself, so ≥ 1
  }

  // Eq. (9): weighted scatter matrix about p_i, then the eigenvalue-ratio tests.
  IssResult result;
  result.saliency.assign(n, 0.0);
  std::vector<double> lambda3(o.fill_budget ? n : 0, 0.0);  // fill_budget's rank for the points the tests turn away
  for (int i = 0; i < n; ++i) {
    search.radius(i, r_frame, nb);
    if (static_cast<int>(nb.size()) - 1 < o.min_neighbors) continue;
    const Eigen::Vector3d pi = set.points[i].cast<double>();
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    double wsum = 0.0;
    for (int j : nb) {
      const Eigen::Vector3d d = set.points[j].cast<double>() - pi;
      cov.noalias() += weight[j] * d * d.transpose();
      wsum += weight[j];
    }
    cov /= wsum;
    const Eigen::Vector3d ev = ascendingEigenvalues(cov);  // one solve for the saliency and the fill's rank
    result.saliency[i] = saliencyOf(ev, o);
    if (o.fill_budget) lambda3[i] = std::max(ev[0], 0.0);
  }

  // Non-maximum suppression on λ3; ties go to the lower index so the outcome
  // never depends on visiting order.
  std::vector<double> margin_weight(o.nms_margin > 0 ? n : 0, 1.0);  // nms_margin's weight per maximum
  for (int i = 0; i < n; ++i) {
    const double s = result.saliency[i];
    if (s <= 0.0) continue;
    search.radius(i, r_nms, nb);
    bool is_max = true;
    double rival = 0.0;  // the most salient other point within r_nms
    for (int j : nb) {
      if (j == i) continue;
      const double t = result.saliency[j];
      if (t > s || (t == s && j < i)) {
        is_max = false;
        break;
      }
      rival = std::max(rival, t);
    }
    if (!is_max) continue;
    result.keypoints.push_back(i);
    if (o.nms_margin > 0) margin_weight[i] = std::min(1.0, (1.0 - rival / s) / o.nms_margin);
  }
  const std::vector<int> maxima = result.keypoints;  // ascending
  if (o.fill_budget && o.max_keypoints > 0 && static_cast<int>(result.keypoints.size()) < o.max_keypoints)
    fillBudget(set, result, lambda3, r_nms, o.max_keypoints);
  const bool weighted = o.budget_taper > 0 && o.max_keypoints > 0;
  double edge = 0.0;  // the saliency of the first keypoint past the budget (0: none)
  if (o.max_keypoints > 0 && static_cast<int>(result.keypoints.size()) > o.max_keypoints) {
    auto& kp = result.keypoints;
    std::stable_sort(kp.begin(), kp.end(), [&](int a, int b) { return result.saliency[a] > result.saliency[b]; });
    edge = result.saliency[kp[static_cast<std::size_t>(o.max_keypoints)]];
    kp.resize(static_cast<std::size_t>(o.max_keypoints));
    std::sort(kp.begin(), kp.end());
  }
  if (!weighted && (result.filled > 0 || o.nms_margin > 0))
    for (int i : result.keypoints)
      result.weight.push_back(std::binary_search(maxima.begin(), maxima.end(), i) ? (o.nms_margin > 0 ? margin_weight[i] : 1.0)
                                                                                  : kFilledWeight);
  if (weighted && !result.keypoints.empty()) {
    // Full weight down to the saliency of the (1 − taper)·budget-th most salient keypoint.
    std::vector<double> s;
    for (int i : result.keypoints) s.push_back(result.saliency[i]);
    std::sort(s.begin(), s.end(), std::greater<double>());
    const std::size_t full =
        std::clamp<std::size_t>(static_cast<std::size_t>(std::lround((1.0 - std::min(o.budget_taper, 1.0)) * o.max_keypoints)),
                                1, s.size());
    const double top = s[full - 1];
    for (int i : result.keypoints)
      result.weight.push_back((top > edge ? std::clamp((result.saliency[i] - edge) / (top - edge), 0.0, 1.0) : 1.0) *
                              (o.nms_margin > 0 ? margin_weight[i] : 1.0));
  }
  return result;
}

}  // namespace keyturn
