#include "keyturn/core/working_resolution.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "keyturn/core/error.h"
#include "voxel_key.h"

namespace keyturn {
namespace {

// The frame the voxel grid is laid in: p ↦ axes^T (p − origin).
struct GridFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

// Principal axes about the centroid. A cubic grid centred on the centroid maps onto itself under
// any swap or sign flip of its axes, so the eigenvectors' order and signs do not matter: the same
// points fall into the same voxels wherever the object lies and however it is turned (up to the
// float rounding of the moved coordinates: a point within ~1e-7 m of a face may cross it, which
// with voxel means moves two means by a fraction of a millimetre and nothing else).
GridFrame objectFrame(const Cloud& cloud, const std::vector<int>& valid, const Eigen::Vector3d& centroid) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i : valid) {
    const Eigen::Vector3d d = cloud.points[i].cast<double>() - centroid;
    cov.noalias() += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  GridFrame f;
  f.origin = centroid;
  if (eig.info() == Eigen::Success) f.axes = eig.eigenvectors();
  return f;
}

}  // namespace

const char* voxelAnchorName(VoxelAnchor anchor) { return anchor == VoxelAnchor::ObjectGrid ? "object" : "camera"; }

const char* voxelPointsName(VoxelPoints points) { return points == VoxelPoints::Means ? "means" : "thinned"; }

VoxelPoints parseVoxelPoints(const std::string& name) {
  if (name == "means") return VoxelPoints::Means;
  if (name == "thinned") return VoxelPoints::Thinned;
  throw Error("must be means or thinned, not '" + name + "'");
}

VoxelAnchor parseVoxelAnchor(const std::string& name) {
  if (name == "object") return VoxelAnchor::ObjectGrid;
  if (name == "camera") return VoxelAnchor::CameraGrid;
  throw Error("must be object or camera, not '" + name + "'");
}

void subsampleToWorkingResolution(Cloud& cloud, const WorkingResolutionOptions& o, WorkingResolutionReport* report) {
  WorkingResolutionReport r;
  std::vector<int> valid;
  valid.reserve(cloud.size());
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (Cloud::isValid(cloud.points[i])) {
      valid.push_back(static_cast<int>(i));
      c += cloud.points[i].cast<double>();
    }
  r.before = r.after = valid.size();
  if (valid.size() >= 2 && o.enabled && o.samples_across > 0) {
    c /= static_cast<double>(valid.size());
    double ss = 0;
    for (int i : valid) ss += (cloud.points[i].cast<double>() - c).squaredNorm();
    r.extent = 2.0 * std::sqrt(ss / static_cast<double>(valid.size()));
    r.spacing = r.extent / o.samples_across;
  }
  if (r.spacing > 0 && std::isfinite(r.spacing)) {
    const bool means = o.points == VoxelPoints::Means;
    const double inv_s = 1.0 / r.spacing;
    const GridFrame frame = o.anchor == VoxelAnchor::ObjectGrid ? objectFrame(cloud, valid, c) : GridFrame{};
    // Every valid point in the grid's frame (double: no rounding from a far origin).
    std::vector<Eigen::Vector3d> q(valid.size());
    for (std::size_t k = 0; k < valid.size(); ++k)
      q[k] = frame.axes.transpose() * (cloud.points[valid[k]].cast<double>() - frame.origin);
    using Cell = Eigen::Matrix<std::int64_t, 3, 1>;
    // The object grid has a voxel centred on the centroid (faces at ±½, ±1½ … sides from it): a
    // plane through the centroid lies inside one layer of voxels, not on a face between two.
    const double offset = o.anchor == VoxelAnchor::ObjectGrid ? 0.5 : 0.0;
    auto cellAt = [offset](const Eigen::Vector3d& p, double inv) {
      return Cell(detail::voxelCell(p.x(), inv, offset), detail::voxelCell(p.y(), inv, offset),
                  detail::voxelCell(p.z(), inv, offset));
    };
    auto cellOf = [&](const Eigen::Vector3d& p) { return cellAt(p, inv_s); };
    auto keyOf = [](const Cell& cell) { return detail::voxelKey(cell.x(), cell.y(), cell.z()); };
    struct Voxel {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int count = 0, best = -1;
      double best_d2 = std::numeric_limits<double>::infinity();
    };
    std::unordered_map<std::uint64_t, Voxel> voxels;
    std::vector<std::uint64_t> key(valid.size());
    auto binInto = [&](double inv) {
      voxels.clear();
      voxels.reserve(valid.size());
      for (std::size_t k = 0; k < valid.size(); ++k) {
        key[k] = keyOf(cellAt(q[k], inv));
        Voxel& v = voxels[key[k]];
        v.sum += q[k];
        ++v.count;
      }
    };
    binInto(inv_s);  // s-voxels decide whether the view is denser than s
    // The camera grid measures in float, as it always has, so specifications written before the
    // object grid existed describe their views exactly as they did.
    const bool camera = o.anchor == VoxelAnchor::CameraGrid;
    auto distance2 = [&](std::size_t k, const Eigen::Vector3d& to) {
      return camera ? static_cast<double>((cloud.points[valid[k]] - to.cast<float>()).squaredNorm())
                    : (q[k] - to).squaredNorm();
    };
    if (static_cast<double>(voxels.size()) < o.keep_fraction * static_cast<double>(valid.size())) {
      if (means) binInto(inv_s / o.mean_voxel);
      for (std::size_t k = 0; k < valid.size(); ++k) {
        Voxel& v = voxels[key[k]];
        const double d2 = distance2(k, v.sum / v.count);
        if (d2 < v.best_d2) {  // ties keep the lower index: the same cloud, the same points
          v.best_d2 = d2;
          v.best = static_cast<int>(k);
        }
      }
      if (means) {
        // Each voxel's mean, at its nearest point's pixel; every other point goes.
        const Eigen::Vector3f nan = Eigen::Vector3f::Constant(std::nanf(""));
        std::vector<Eigen::Vector3f> mean_at(cloud.size(), nan);
        for (const auto& [k, v] : voxels)
          if (v.best >= 0)  // none when every distance overflowed (points near float's limit)
            mean_at[static_cast<std::size_t>(valid[v.best])] =
              (frame.axes * (v.sum / v.count) + frame.origin).cast<float>();
        for (int i : valid) cloud.points[i] = mean_at[static_cast<std::size_t>(i)];
        r.subsampled = true;
        r.off_pixel_rays = cloud.organized();
        r.after = voxels.size();
        if (report) *report = r;
        return;
      }
      // Voxel representatives of neighbouring voxels can lie much closer than s (0.6 s on average),
      // which would fill every r-ball with ~2.5× the neighbours a sensor at spacing s gives. So the
      // representatives are thinned to at least s apart, in index order (deterministic; row by row
      // for an organized view), as a sensor at spacing s would sample the surface.
      std::vector<int> reps;  // positions in `valid`
      reps.reserve(voxels.size());
      for (const auto& [k, v] : voxels)
        if (v.best >= 0) reps.push_back(v.best);
      std::sort(reps.begin(), reps.end());
      std::unordered_map<std::uint64_t, std::vector<int>> kept_in;
      kept_in.reserve(reps.size());
      const double s2 = camera ? static_cast<double>(static_cast<float>(r.spacing * r.spacing)) : r.spacing * r.spacing;
      std::vector<char> keep(cloud.size(), 0);
      std::size_t kept = 0;
      for (int k : reps) {
        const auto cell = cellOf(q[k]);
        bool near = false;
        for (std::int64_t dx = -1; dx <= 1 && !near; ++dx)
          for (std::int64_t dy = -1; dy <= 1 && !near; ++dy)
            for (std::int64_t dz = -1; dz <= 1 && !near; ++dz) {
              const auto it = kept_in.find(detail::voxelKey(cell.x() + dx, cell.y() + dy, cell.z() + dz));
              if (it == kept_in.end()) continue;
              for (int j : it->second)
                if ((camera ? static_cast<double>((cloud.points[valid[j]] - cloud.points[valid[k]]).squaredNorm())
                            : (q[j] - q[k]).squaredNorm()) < s2) {
                  near = true;
                  break;
                }
            }
        if (near) continue;
        kept_in[keyOf(cell)].push_back(k);
        keep[static_cast<std::size_t>(valid[k])] = 1;
        ++kept;
      }
      const Eigen::Vector3f nan = Eigen::Vector3f::Constant(std::nanf(""));
      for (int i : valid)
        if (!keep[static_cast<std::size_t>(i)]) cloud.points[i] = nan;
      r.subsampled = true;
      r.after = kept;
    }
  }
  if (report) *report = r;
}

}  // namespace keyturn
