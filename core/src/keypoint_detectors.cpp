// The detectors keyturn compares against: its own ISS, PCL's uniform sampling, and PCL's Harris3D
// and SIFT3D (in the plugin "pcl_features", src/pcl_features_plugin.h).
#include "keyturn/core/keypoint_detectors.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/filters/uniform_sampling.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "keyturn/core/error.h"
#include "keyturn/core/radius_search.h"
#include "pcl_features_plugin.h"
#include "pcl_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <tuple>

namespace keyturn {

Detector parseDetector(const std::string& n) {
  if (n == "iss") return Detector::Iss;
  if (n == "harris3d") return Detector::Harris3d;
  if (n == "sift3d") return Detector::Sift3d;
  if (n == "uniform") return Detector::Uniform;
  if (n == "iss-chain") return Detector::IssChain;
  if (n == "iss-refined") return Detector::IssRefined;
  if (n == "iss-nearest") return Detector::IssNearest;
  if (n == "iss-salient") return Detector::IssSalient;
  if (n == "iss-measured") return Detector::IssMeasured;
  throw Error("unknown detector '" + n +
              "' (expected iss, harris3d, sift3d, uniform, iss-chain, iss-refined, iss-nearest, iss-salient, "
              "iss-measured)");
}

std::string detectorName(Detector d) {
  switch (d) {
    case Detector::Iss: return "iss";
    case Detector::Harris3d: return "harris3d";
    case Detector::Sift3d: return "sift3d";
    case Detector::Uniform: return "uniform";
    case Detector::IssChain: return "iss-chain";
    case Detector::IssRefined: return "iss-refined";
    case Detector::IssNearest: return "iss-nearest";
    case Detector::IssSalient: return "iss-salient";
    case Detector::IssMeasured: return "iss-measured";
  }
  return "?";
}

namespace {
using detail::toPcl;

// Harris's response at every point (no suppression), in the set's order.
std::vector<double> harrisResponse(const PointSet& set, double res, const DetectorOptions& o) {
  const auto all = detail::pclFeatures().harris(set, o.harris_radius * res, false);
  std::vector<double> out(set.size(), 0.0);
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(toPcl(set.points));
  pcl::Indices idx(1);
  std::vector<float> d2(1);
  for (const auto& [p, response] : all)
    if (p.allFinite() && std::isfinite(response) &&
        tree.nearestKSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), 1, idx, d2) == 1)
      out[static_cast<std::size_t>(idx[0])] = response;
  return out;
}

// |curvature| at every point, from the normals SIFT's scale space is built on.
std::vector<double> curvature(const PointSet& set, double res) {
  const std::vector<float> n = detail::pclFeatures().curvature(set, 3.5 * res);
  std::vector<double> out(set.size(), 0.0);
  for (std::size_t i = 0; i < n.size() && i < out.size(); ++i) out[i] = std::isfinite(n[i]) ? std::abs(n[i]) : 0.0;
  return out;
}

// The first of each run of keypoints at one position, in order: SIFT reports a point once per scale
// it is found at, and repeatability counts locations.
void dropRepeatedPositions(std::vector<Eigen::Vector3f>& kp) {
  std::set<std::tuple<float, float, float>> seen;
  kp.erase(std::remove_if(kp.begin(), kp.end(), [&](const Eigen::Vector3f& p) { return !seen.emplace(p.x(), p.y(), p.z()).second; }),
           kp.end());
}

float minDistance(const Eigen::Vector3f& p, const std::vector<Eigen::Vector3f>& chosen) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& c : chosen) best = std::min(best, (c - p).squaredNorm());
  return std::sqrt(best);
}

// Greedy farthest-point order: each next point the farthest from those chosen.
void farthestPoints(const std::vector<Eigen::Vector3f>& pool, std::size_t k, std::vector<Eigen::Vector3f>& chosen) {
  if (pool.empty()) return;
  std::vector<float> d(pool.size());
  if (chosen.empty()) {
    Eigen::Vector3f c = Eigen::Vector3f::Zero();
    for (const auto& p : pool) c += p / static_cast<float>(pool.size());
    std::size_t first = 0;
    for (std::size_t i = 1; i < pool.size(); ++i)
      if ((pool[i] - c).squaredNorm() < (pool[first] - c).squaredNorm()) first = i;
    chosen.push_back(pool[first]);
  }
  for (std::size_t i = 0; i < pool.size(); ++i) d[i] = minDistance(pool[i], chosen);
  while (chosen.size() < k) {
    const std::size_t far = static_cast<std::size_t>(std::max_element(d.begin(), d.end()) - d.begin());
    if (d[far] <= 0.f) break;  // every pool point already chosen
    chosen.push_back(pool[far]);
    for (std::size_t i = 0; i < pool.size(); ++i) d[i] = std::min(d[i], (pool[i] - pool[far]).norm());
  }
}
}  // namespace

std::vector<Eigen::Vector3f> detectKeypoints(Detector d, const PointSet& set, double res, const DetectorOptions& o) {
  std::vector<Eigen::Vector3f> out;
  if (set.size() < 10) return out;
  switch (d) {
    case Detector::Iss:
    case Detector::IssChain:
    case Detector::IssRefined:
    case Detector::IssNearest:
    case Detector::IssSalient:
    case Detector::IssMeasured: {
      const RadiusSearch search(set);
      for (int i : detectIssKeypoints(set, search, res, o.iss).keypoints) out.push_back(set.points[i]);
      break;
    }
    case Detector::Harris3d:
      for (const auto& [p, response] : detail::pclFeatures().harris(set, o.harris_radius * res, true))
        if (std::isfinite(p.x())) out.push_back(p);
      break;
    case Detector::Sift3d:
      out = detail::pclFeatures().sift(set, 3.5 * res, static_cast<float>(o.sift_min_scale * res), o.sift_octaves,
                                       o.sift_scales_per_octave, static_cast<float>(o.sift_min_contrast));
      break;
    case Detector::Uniform: {
      auto cloud = toPcl(set.points);
      pcl::UniformSampling<pcl::PointXYZ> us;
      us.setInputCloud(cloud);
      us.setRadiusSearch(o.uniform_radius * res);
      pcl::PointCloud<pcl::PointXYZ> kp;
      us.filter(kp);
      for (const auto& p : kp) out.emplace_back(p.x, p.y, p.z);
      break;
    }
  }
  dropRepeatedPositions(out);
  return out;
}

std::vector<Eigen::Vector3f> detectKeypointsAtBudget(Detector d, const PointSet& set, double res, int k,
                                                     const DetectorOptions& o) {
  const std::size_t want = std::min<std::size_t>(static_cast<std::size_t>(std::max(k, 0)), set.size());
  std::vector<Eigen::Vector3f> chosen;
  if (want == 0) return chosen;
  DetectorOptions uncapped = o;
  uncapped.iss.max_keypoints = 0;
  const std::vector<Eigen::Vector3f> native = detectKeypoints(d, set, res, uncapped);
  if (d == Detector::Uniform) {
    farthestPoints(native, want, chosen);
    farthestPoints(set.points, want, chosen);
    return chosen;
  }
  std::vector<double> score;
  double radius = 0;  // the detector's suppression radius, metres
  if (isIssOnSomeView(d)) {
    const RadiusSearch search(set);
    score = detectIssKeypoints(set, search, res, uncapped.iss).saliency;
    radius = o.iss.nms_radius * res;
  } else if (d == Detector::Harris3d) {
    score = harrisResponse(set, res, o);
    radius = o.harris_radius * res;
  } else {
    score = curvature(set, res);
    radius = 2 * o.sift_min_scale * res;
  }
  // Native keypoints ranked by the score of the point they stand on (or nearest).
  auto cloud = toPcl(set.points);
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  pcl::Indices idx(1);
  std::vector<float> d2(1);
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t i = 0; i < native.size(); ++i) {
    const auto& p = native[i];
    const double s = tree.nearestKSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), 1, idx, d2) == 1
                         ? score[static_cast<std::size_t>(idx[0])] : 0.0;
    ranked.emplace_back(s, i);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& [s, i] : ranked) {
    if (chosen.size() == want) break;
    chosen.push_back(native[i]);
  }
  // Too few: the most salient other points, spread by the suppression radius.
  std::vector<std::size_t> order(set.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return score[a] > score[b]; });
  std::vector<char> used(set.size(), 0);
  for (float r = static_cast<float>(radius); chosen.size() < want; r *= 0.5f) {
    for (std::size_t i : order) {
      if (chosen.size() == want) break;
      if (used[i] || (r > 1e-6f && minDistance(set.points[i], chosen) < r)) continue;
      if (r <= 1e-6f && minDistance(set.points[i], chosen) == 0.f) continue;  // the same point twice
      used[i] = 1;
      chosen.push_back(set.points[i]);
    }
    if (r <= 1e-6f) break;
  }
  return chosen;
}

}  // namespace keyturn
