#include "keyturn/core/keypoint_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <unordered_map>

#include "voxel_key.h"
#include "weighted_scatter.h"

namespace keyturn {
namespace {

// The measured points in a hash grid of cubes of side r, stored cube by cube (coordinates in
// float, contiguous per cube, so a scan is one tight loop): counts within r (ISS's density weights)
// and nearest distances, each a scan of the 27 cubes around a point, computed only for the points
// refinement visits.
class MeasuredGrid {
 public:
  MeasuredGrid(const PointSet& set, double r)
      : set_(set), r2_(static_cast<float>(r * r)), inv_(1.0 / r), count_(set.size(), 0) {
    const std::size_t n = set.size();
    std::vector<std::pair<std::uint64_t, int>> keyed(n);
    for (std::size_t i = 0; i < n; ++i) keyed[i] = {keyOf(set.points[i], 0, 0, 0), static_cast<int>(i)};
    std::sort(keyed.begin(), keyed.end());
    x_.resize(n), y_.resize(n), z_.resize(n), index_.resize(n);
    for (std::size_t a = 0; a < n; ++a) {
      const auto& p = set.points[static_cast<std::size_t>(keyed[a].second)];
      x_[a] = p.x(), y_[a] = p.y(), z_[a] = p.z(), index_[a] = keyed[a].second;
      if (a == 0 || keyed[a].first != keyed[a - 1].first) cells_[keyed[a].first] = {static_cast<int>(a), static_cast<int>(a)};
      cells_[keyed[a].first].second = static_cast<int>(a + 1);
    }
  }
  // Points within r of point i, itself included (≥ 1). Counted for the whole cube holding i at
  // once: its points share the 27 cubes around it, so the hash lookups (a third of the refinement's
  // time when made per point) are made once per cube.
  int count(int i) {
    if (count_[static_cast<std::size_t>(i)] == 0) countCube(i);
    return count_[static_cast<std::size_t>(i)];
  }
  // Distance to the nearest other point within r; +inf when none is.
  double nearest(int i) const {
    const Eigen::Vector3f& p = set_.points[static_cast<std::size_t>(i)];
    float best = r2_;
    bool found = false;
    forEachCell(p, [&](int begin, int end) {
      for (int a = begin; a < end; ++a) {
        const float dx = x_[a] - p.x(), dy = y_[a] - p.y(), dz = z_[a] - p.z();
        const float d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < best && index_[a] != i) best = d2, found = true;
      }
    });
    return found ? std::sqrt(static_cast<double>(best)) : std::numeric_limits<double>::infinity();
  }

 private:
  template <typename F>
  void forEachCell(const Eigen::Vector3f& p, F&& f) const {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(keyOf(p, dx, dy, dz));
          if (it != cells_.end()) f(it->second.first, it->second.second);
        }
  }
  void countCube(int i) {
    const Eigen::Vector3f& p = set_.points[static_cast<std::size_t>(i)];
    std::pair<int, int> around[27];
    int m = 0;
    forEachCell(p, [&](int begin, int end) { around[m++] = {begin, end}; });
    const auto [begin, end] = cells_.at(keyOf(p, 0, 0, 0));
    for (int b = begin; b < end; ++b) {
      int c = 0;
      for (int r = 0; r < m; ++r) {
        int k = 0;
        for (int a = around[r].first; a < around[r].second; ++a) {
          const float dx = x_[a] - x_[b], dy = y_[a] - y_[b], dz = z_[a] - z_[b];
          k += dx * dx + dy * dy + dz * dz < r2_;
        }
        c += k;
      }
      count_[static_cast<std::size_t>(index_[b])] = c;
    }
  }
  std::uint64_t keyOf(const Eigen::Vector3f& p, int dx, int dy, int dz) const {
    return detail::voxelKey(detail::voxelCell(p.x(), inv_, 0.0) + dx, detail::voxelCell(p.y(), inv_, 0.0) + dy,
                            detail::voxelCell(p.z(), inv_, 0.0) + dz);
  }
  const PointSet& set_;
  float r2_;
  double inv_;
  std::vector<int> count_;
  std::vector<float> x_, y_, z_;
  std::vector<int> index_;
  std::unordered_map<std::uint64_t, std::pair<int, int>> cells_;  // cube → its range in x_, y_, z_
};

// One stage at one scale (`unit`: the resolution ISS's radii are multiples of): each keypoint
// moved to the measured point of greatest λ3 within `window` metres of it. With measure_spacing,
// returns the mean nearest-neighbour distance of every fourth candidate (in index order): the
// measured resolution where the keypoints are; else 0.
double refineAtScale(const PointSet& measured, std::vector<Eigen::Vector3f>& kp, double unit, double window,
                     const IssOptions& iss, bool measure_spacing) {
  const int n = static_cast<int>(measured.size());
  const double r_frame = iss.frame_radius * unit;
  const double reach = window + r_frame;  // every neighbour of every candidate of a keypoint
  const double frame2 = r_frame * r_frame;
  const float window2 = static_cast<float>(window * window), reach2 = static_cast<float>(reach * reach);

  // Per keypoint: its candidates (within the window; a point in two windows goes to the nearer
  // keypoint, so two keypoints never land on one point) and every measured point within reach.
  std::vector<std::vector<int>> candidates(kp.size()), near(kp.size());
  const std::size_t K = kp.size();
  std::vector<float> kx(K), ky(K), kz(K), d2(K);  // by coordinate: the distance loop vectorizes
  for (std::size_t k = 0; k < K; ++k) kx[k] = kp[k].x(), ky[k] = kp[k].y(), kz[k] = kp[k].z();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = measured.points[static_cast<std::size_t>(i)];
    for (std::size_t k = 0; k < K; ++k) {
      const float dx = kx[k] - p.x(), dy = ky[k] - p.y(), dz = kz[k] - p.z();
      d2[k] = dx * dx + dy * dy + dz * dz;
    }
    int best = -1;
    float best_d2 = window2;
    for (std::size_t k = 0; k < K; ++k) {
      if (d2[k] >= reach2) continue;
      near[k].push_back(i);
      if (d2[k] < best_d2) best_d2 = d2[k], best = static_cast<int>(k);
    }
    if (best >= 0) candidates[static_cast<std::size_t>(best)].push_back(i);
  }

  MeasuredGrid grid(measured, iss.density_radius * unit);
  double spacing_sum = 0;
  int spacing_count = 0;
  detail::ScatterNeighbours q;
  for (std::size_t k = 0; k < kp.size(); ++k) {
    if (candidates[k].empty()) continue;
    q.clear();
    for (int j : near[k])  // Eq. (8), as ISS weighs its neighbours
      q.add(measured.points[static_cast<std::size_t>(j)].cast<double>(), 1.0 / grid.count(j));
    q.pad();
    double best_s = 0.0;
    int best = -1;
    for (std::size_t c = 0; c < candidates[k].size(); ++c) {  // ascending: ties keep the lower index
      const int i = candidates[k][c];
      if (measure_spacing && c % 4 == 0)
        if (const double d = grid.nearest(i); std::isfinite(d)) spacing_sum += d, ++spacing_count;
      // Eq. (9): the weighted scatter about p_i of its neighbours within r_frame.
      const detail::WeightedScatter s =
          detail::weightedScatter(q, measured.points[static_cast<std::size_t>(i)].cast<double>(), frame2);
      if (s.count - 1 < iss.min_neighbors) continue;  // count holds p_i itself
      const Eigen::Matrix3d cov = s.scatter / s.weight;
      const double saliency = issSaliency(cov, iss);
      if (saliency > best_s) best_s = saliency, best = i;
    }
    if (best >= 0) kp[k] = measured.points[static_cast<std::size_t>(best)];
  }
  return spacing_count > 0 ? spacing_sum / spacing_count : 0.0;
}

}  // namespace

std::vector<Eigen::Vector3f> refineKeypointsOnMeasuredPoints(const PointSet& measured,
                                                             const std::vector<Eigen::Vector3f>& keypoints,
                                                             double working_resolution, const IssOptions& iss,
                                                             const KeypointRefinementOptions& o) {
  std::vector<Eigen::Vector3f> out = keypoints;
  if (keypoints.empty() || measured.size() < 2 || !(working_resolution > 0)) return out;
  const double measured_spacing =
      refineAtScale(measured, out, working_resolution, o.window * iss.nms_radius * working_resolution, iss, true);
  if (o.fine_scale > 0 && measured_spacing > 0) {
    const double unit = o.fine_scale * measured_spacing;
    refineAtScale(measured, out, unit, o.fine_window * iss.nms_radius * unit, iss, false);
  }
  return out;
}

}  // namespace keyturn
