#include "keyturn/core/working_resolution.h"

#include "voxel_key.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace keyturn {
namespace {

std::uint64_t voxelKey(const Eigen::Vector3f& p, double inv_s) {
  return detail::voxelKey(detail::voxelCell(p.x(), inv_s), detail::voxelCell(p.y(), inv_s), detail::voxelCell(p.z(), inv_s));
}

}  // namespace

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
  if (r.spacing > 0) {
    const double inv_s = 1.0 / r.spacing;
    struct Voxel {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int count = 0, best = -1;
      float best_d2 = std::numeric_limits<float>::infinity();
    };
    std::unordered_map<std::uint64_t, Voxel> voxels;
    voxels.reserve(valid.size());
    std::vector<std::uint64_t> key(valid.size());
    for (std::size_t k = 0; k < valid.size(); ++k) {
      key[k] = voxelKey(cloud.points[valid[k]], inv_s);
      Voxel& v = voxels[key[k]];
      v.sum += cloud.points[valid[k]].cast<double>();
      ++v.count;
    }
    if (static_cast<double>(voxels.size()) < o.keep_fraction * static_cast<double>(valid.size())) {
      for (std::size_t k = 0; k < valid.size(); ++k) {
        Voxel& v = voxels[key[k]];
        const Eigen::Vector3f mean = (v.sum / v.count).cast<float>();
        const float d2 = (cloud.points[valid[k]] - mean).squaredNorm();
        if (d2 < v.best_d2) {  // ties keep the lower index: the same cloud, the same points
          v.best_d2 = d2;
          v.best = valid[k];
        }
      }
      // Voxel representatives of neighbouring voxels can lie much closer than s (0.6 s on average),
      // which would fill every r-ball with ~2.5× the neighbours a sensor at spacing s gives. So the
      // representatives are thinned to at least s apart, in index order (deterministic; row by row
      // for an organized view), as a sensor at spacing s would sample the surface.
      std::vector<int> reps;
      reps.reserve(voxels.size());
      for (const auto& [k, v] : voxels) reps.push_back(v.best);
      std::sort(reps.begin(), reps.end());
      std::unordered_map<std::uint64_t, std::vector<int>> kept_in;
      kept_in.reserve(reps.size());
      const float s2 = static_cast<float>(r.spacing * r.spacing);
      std::vector<char> keep(cloud.size(), 0);
      std::size_t kept = 0;
      for (int i : reps) {
        const Eigen::Vector3f& p = cloud.points[i];
        const std::int64_t cx = detail::voxelCell(p.x(), inv_s), cy = detail::voxelCell(p.y(), inv_s),
                           cz = detail::voxelCell(p.z(), inv_s);
        bool near = false;
        for (std::int64_t dx = -1; dx <= 1 && !near; ++dx)
          for (std::int64_t dy = -1; dy <= 1 && !near; ++dy)
            for (std::int64_t dz = -1; dz <= 1 && !near; ++dz) {
              const auto it = kept_in.find(detail::voxelKey(cx + dx, cy + dy, cz + dz));
              if (it == kept_in.end()) continue;
              for (int j : it->second)
                if ((cloud.points[j] - p).squaredNorm() < s2) {
                  near = true;
                  break;
                }
            }
        if (near) continue;
        kept_in[detail::voxelKey(cx, cy, cz)].push_back(i);
        keep[static_cast<std::size_t>(i)] = 1;
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
