#include "keyturn/core/measured_keypoints.h"

#include <limits>

#include "keyturn/core/radius_search.h"

namespace keyturn {

MeasuredKeypoints detectKeypointsOnMeasuredPoints(const PointSet& measured, const PointSet& working,
                                                  double working_resolution, const IssOptions& iss) {
  MeasuredKeypoints out;
  if (measured.size() < 2 || working.size() == 0) return out;
  RadiusSearch search(measured);
  IssResult r = detectIssKeypoints(measured, search, working_resolution, iss);
  out.filled = r.filled;
  std::vector<bool> taken(working.size(), false);
  for (std::size_t k = 0; k < r.keypoints.size(); ++k) {
    const Eigen::Vector3f& p = measured.points[static_cast<std::size_t>(r.keypoints[k])];
    int best = -1;
    float best_d2 = std::numeric_limits<float>::infinity();
    for (std::size_t v = 0; v < working.size(); ++v) {
      const float d2 = (working.points[v] - p).squaredNorm();
      if (!taken[v] && d2 < best_d2) best_d2 = d2, best = static_cast<int>(v);
    }
    if (best < 0) break;
    taken[static_cast<std::size_t>(best)] = true;
    out.positions.push_back(p);
    out.vertex.push_back(best);
    if (!r.weight.empty()) out.weight.push_back(r.weight[k]);
  }
  return out;
}

}  // namespace keyturn
