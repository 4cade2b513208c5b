#pragma once
// The k nearest neighbours of every point of a set at once, exactly, from a hash grid: what the
// statistical outlier filter and the cloud resolution ask a k-d tree point by point.
#include <Eigen/Core>
#include <vector>

namespace keyturn {

// For each point, the squared distances to its k nearest points of the set, itself included (so
// the first is 0), ascending: n × min(k, n) values, point by point. The distances are summed as
// FLANN's L2_Simple sums them ((dx² + dy²) + dz², query minus point), so they are the values PCL's
// exact k-d tree gives (tested). Points must be finite.
std::vector<float> nearestSquaredDistances(const std::vector<Eigen::Vector3f>& points, int k);

}  // namespace keyturn
