#include "keyturn/core/keypoint_placement.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "keyturn/core/error.h"
#include "keyturn/core/median.h"
#include "voxel_key.h"

namespace keyturn {

const char* keypointPlacementName(KeypointPlacement p) {
  switch (p) {
    case KeypointPlacement::Nearest: return "nearest";
    case KeypointPlacement::Salient: return "salient";
    case KeypointPlacement::Measured: return "measured";
    default: return "means";
  }
}

KeypointPlacement parseKeypointPlacement(const std::string& name) {
  if (name == "means") return KeypointPlacement::VoxelMeans;
  if (name == "nearest") return KeypointPlacement::Nearest;
  if (name == "salient") return KeypointPlacement::Salient;
  if (name == "measured") return KeypointPlacement::Measured;
  throw Error("must be means, nearest, salient or measured, not '" + name + "'");
}

namespace {

// Cubes of one side over some of the measured points, in the view's own frame (centroid and
// principal axes, so that a rigid motion of the view keeps the same cubes): per cube its points and
// their moments per unit mass, each cube weighing 1 in a saliency as ISS's density weights make
// each patch of surface weigh the same however densely it is sampled.
struct Cubes {
  std::vector<double> x, y, z;                  // mean
  std::vector<double> xx, xy, xz, yy, yz, zz;   // scatter about the mean ÷ count
  std::vector<double> n;                        // count
  std::vector<std::vector<int>> points;

  Cubes(const std::vector<Eigen::Vector3d>& q, const std::vector<int>& subset, double side) {
    std::unordered_map<std::uint64_t, int> index;
    index.reserve(subset.size());
    const double inv = 1.0 / side;
    for (int i : subset) {
      const auto key = detail::voxelKey(detail::voxelCell(q[i].x(), inv), detail::voxelCell(q[i].y(), inv),
                                        detail::voxelCell(q[i].z(), inv));
      const auto [it, fresh] = index.emplace(key, static_cast<int>(points.size()));
      if (fresh) points.emplace_back();
      points[static_cast<std::size_t>(it->second)].push_back(i);
    }
    const std::size_t m = points.size();
    for (auto* v : {&x, &y, &z, &xx, &xy, &xz, &yy, &yz, &zz, &n}) v->assign(m, 0.0);
    for (std::size_t c = 0; c < m; ++c) {
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int i : points[c]) mean += q[i];
      mean /= static_cast<double>(points[c].size());
      Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
      for (int i : points[c]) s.noalias() += (q[i] - mean) * (q[i] - mean).transpose();
      s /= static_cast<double>(points[c].size());
      x[c] = mean.x(), y[c] = mean.y(), z[c] = mean.z(), n[c] = static_cast<double>(points[c].size());
      xx[c] = s(0, 0), xy[c] = s(0, 1), xz[c] = s(0, 2), yy[c] = s(1, 1), yz[c] = s(1, 2), zz[c] = s(2, 2);
    }
  }
  std::size_t size() const { return n.size(); }
};

// The cubes (indices) whose mean lies within `reach` of p.
std::vector<int> cubesNear(const Cubes& c, const Eigen::Vector3d& p, double reach) {
  std::vector<int> out;
  const double r2 = reach * reach;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double dx = c.x[k] - p.x(), dy = c.y[k] - p.y(), dz = c.z[k] - p.z();
    if (dx * dx + dy * dy + dz * dz <= r2) out.push_back(static_cast<int>(k));
  }
  return out;
}

// ISS's λ3 at p from the cubes `near`: each cube weighs 1 inside r − side/2, 0 beyond r + side/2
// and linearly between (by its mean's distance), so a cube enters the frame gradually.
double cubeSaliency(const Cubes& c, const std::vector<int>& near, const Eigen::Vector3d& p, double r, double side,
                    const IssOptions& iss) {
  const double lo = r - 0.5 * side, hi = r + 0.5 * side;
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0, wsum = 0, mass = 0;
  for (int k : near) {
    const double dx = c.x[k] - p.x(), dy = c.y[k] - p.y(), dz = c.z[k] - p.z();
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (d >= hi) continue;
    const double w = d <= lo ? 1.0 : (hi - d) / side;
    xx += w * (c.xx[k] + dx * dx), xy += w * (c.xy[k] + dx * dy), xz += w * (c.xz[k] + dx * dz);
    yy += w * (c.yy[k] + dy * dy), yz += w * (c.yz[k] + dy * dz), zz += w * (c.zz[k] + dz * dz);
    wsum += w, mass += w * c.n[k];
  }
  if (mass - 1 < iss.min_neighbors || wsum <= 0) return 0.0;
  Eigen::Matrix3d cov;
  cov << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  return issSaliency(cov / wsum, iss);
}

// The points of `cubes` within `radius` of p, at most `most` of them (every n-th in index order).
std::vector<int> pointsWithin(const Cubes& cubes, const std::vector<int>& near, const std::vector<Eigen::Vector3d>& q,
                              const Eigen::Vector3d& p, double radius, int most) {
  std::vector<int> out;
  for (int k : near)
    for (int i : cubes.points[static_cast<std::size_t>(k)])
      if ((q[i] - p).squaredNorm() <= radius * radius) out.push_back(i);
  std::sort(out.begin(), out.end());
  if (most > 0 && static_cast<int>(out.size()) > most) {
    const std::size_t stride = (out.size() + most - 1) / static_cast<std::size_t>(most);
    std::vector<int> kept;
    for (std::size_t a = 0; a < out.size(); a += stride) kept.push_back(out[a]);
    out.swap(kept);
  }
  return out;
}

// The candidate of greatest saliency not yet taken (ties: the lower index); -1 when none is salient.
int mostSalient(const Cubes& cubes, const std::vector<int>& near, const std::vector<Eigen::Vector3d>& q,
                const std::vector<int>& candidates, double r_frame, double side, const IssOptions& iss,
                const std::unordered_set<int>& taken) {
  double best_s = 0.0;
  int best = -1;
  for (int i : candidates) {
    if (taken.count(i)) continue;
    const double s = cubeSaliency(cubes, near, q[i], r_frame, side, iss);
    if (s > best_s) best_s = s, best = i;
  }
  return best;
}

}  // namespace

std::vector<Eigen::Vector3f> placeKeypoints(const PointSet& measured, const std::vector<Eigen::Vector3f>& keypoints,
                                            double s, const IssOptions& iss, const KeypointPlacementOptions& o) {
  std::vector<Eigen::Vector3f> out = keypoints;
  const int n = static_cast<int>(measured.size());
  if (o.placement == KeypointPlacement::VoxelMeans || o.placement == KeypointPlacement::Measured || keypoints.empty() || n < 2 || !(s > 0)) return out;

  // The view's own frame: centroid and principal axes.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : measured.points) centroid += p.cast<double>();
  centroid /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : measured.points) cov.noalias() += (p.cast<double>() - centroid) * (p.cast<double>() - centroid).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Matrix3d axes = eig.info() == Eigen::Success ? eig.eigenvectors() : Eigen::Matrix3d::Identity();
  std::vector<Eigen::Vector3d> q(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) q[i] = axes.transpose() * (measured.points[i].cast<double>() - centroid);
  auto local = [&](const Eigen::Vector3f& p) -> Eigen::Vector3d { return axes.transpose() * (p.cast<double>() - centroid); };

  std::vector<int> all(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) all[i] = i;
  const double side = o.cube * s;
  const Cubes coarse(q, all, side);
  const double diag = std::sqrt(3.0) * side;  // a cube's mean lies within this of any of its points
  std::unordered_set<int> taken;

  if (o.placement == KeypointPlacement::Nearest) {
    for (std::size_t k = 0; k < keypoints.size(); ++k) {
      const Eigen::Vector3d p = local(keypoints[k]);
      double best_d2 = std::numeric_limits<double>::infinity();
      int best = -1;
      for (double reach = 2 * side; best < 0 && reach < 64 * side; reach *= 2)
        for (int c : cubesNear(coarse, p, reach))
          for (int i : coarse.points[static_cast<std::size_t>(c)])
            if (const double d2 = (q[i] - p).squaredNorm(); d2 < best_d2 && !taken.count(i)) best_d2 = d2, best = i;
      if (best >= 0) out[k] = measured.points[best], taken.insert(best);
    }
    return out;
  }

  // Coarse stage: at the chain's scale, the most salient of the measured points near each keypoint.
  const double r_frame = iss.frame_radius * s, window = o.window * iss.nms_radius * s;
  std::vector<int> at(keypoints.size(), -1);
  std::vector<double> spacing;  // per keypoint: the measured spacing its window's count gives
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    const Eigen::Vector3d p = local(keypoints[k]);
    const std::vector<int> near = cubesNear(coarse, p, window + r_frame + side);
    const std::vector<int> inside = pointsWithin(coarse, near, q, p, window, 0);
    // A ball about a surface point cuts a disc of area π window² from it, whatever its tilt.
    if (inside.size() >= 4) spacing.push_back(std::sqrt(M_PI * window * window / static_cast<double>(inside.size())));
    const std::vector<int> candidates = pointsWithin(coarse, near, q, p, window, o.coarse_candidates);
    at[k] = mostSalient(coarse, near, q, candidates, r_frame, side, iss, taken);
    if (at[k] >= 0) taken.insert(at[k]);
  }
  if (o.fine_scale > 0 && !spacing.empty()) {
    const double u = o.fine_scale * upperMedian(spacing), fside = o.cube * u;
    const double fr = iss.frame_radius * u, fw = o.fine_window * iss.nms_radius * u;
    taken.clear();
    for (std::size_t k = 0; k < keypoints.size(); ++k) {
      if (at[k] < 0) continue;
      const Eigen::Vector3d p = q[at[k]];
      // The measured points any candidate's frame reaches, in cubes of the fine side.
      const double reach = fw + fr + fside;
      const Cubes fine(q, pointsWithin(coarse, cubesNear(coarse, p, reach + diag), q, p, reach, 0), fside);
      const std::vector<int> near = cubesNear(fine, p, reach);
      const std::vector<int> candidates = pointsWithin(fine, near, q, p, fw, o.fine_candidates);
      const int best = mostSalient(fine, near, q, candidates, fr, fside, iss, taken);
      if (best >= 0) at[k] = best;
      taken.insert(at[k]);
    }
  }
  for (std::size_t k = 0; k < keypoints.size(); ++k)
    if (at[k] >= 0) out[k] = measured.points[static_cast<std::size_t>(at[k])];
  return out;
}

}  // namespace keyturn
