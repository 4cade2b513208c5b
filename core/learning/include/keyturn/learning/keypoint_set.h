#pragma once
// The "kpset" feature block: a view's keypoints themselves, for a network that learns its own set
// function over them (set_network_classifier.h) where the PDFs histogram them by fixed bins.
// K, then the first kKeypointSetSize keypoints (x, y, z in metres, centred on their centroid, in
// describe's order), zeros past K. describe's budget is 64 keypoints (IssOptions::max_keypoints).
#include <Eigen/Core>
#include <vector>

namespace keyturn::learning {

constexpr int kKeypointSetSize = 64;
constexpr int kKeypointSetWidth = 1 + 3 * kKeypointSetSize;

std::vector<double> keypointSetBlock(const std::vector<Eigen::Vector3f>& keypoints);

}  // namespace keyturn::learning
