#include "keyturn/learning/keypoint_set.h"

#include <algorithm>

namespace keyturn::learning {

std::vector<double> keypointSetBlock(const std::vector<Eigen::Vector3f>& keypoints) {
  std::vector<double> block(kKeypointSetWidth, 0.0);
  const std::size_t n = keypoints.size();
  const std::size_t k = std::min<std::size_t>(n, kKeypointSetSize);
  block[0] = static_cast<double>(k);
  if (k == 0) return block;
  // Past the block's size, every (n / k)-th keypoint: describe's order follows the points', so a
  // stride covers the whole view where the first k would cover part of it.
  auto pick = [&](std::size_t i) -> const Eigen::Vector3f& { return keypoints[i * n / k]; };
  // Centred: the block is then the same wherever the object stands (the network's inputs are
  // distances and angles, invariant anyway; the file's values stay small).
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < k; ++i) centroid += pick(i).cast<double>();
  centroid /= static_cast<double>(k);
  for (std::size_t i = 0; i < k; ++i) {
    const Eigen::Vector3d p = pick(i).cast<double>() - centroid;
    for (int c = 0; c < 3; ++c) block[1 + 3 * i + static_cast<std::size_t>(c)] = p[c];
  }
  return block;
}

}  // namespace keyturn::learning
