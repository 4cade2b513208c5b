#pragma once
// The "kpset" feature block: a view's keypoints themselves, for a network that learns its own set
// function over them (set_network_classifier.h) where the PDFs histogram them by fixed bins.
// K, then up to kKeypointSetSize keypoints (x, y, z in metres, centred on their centroid, in
// describe's order), zeros past K. With more keypoints than that (describe's budget is 128 since
// 2026-12-07, DescriptorOptions), every (K / kKeypointSetSize)-th of them.
#include <Eigen/Core>
#include <vector>

namespace keyturn::learning {

constexpr int kKeypointSetSize = 64;
constexpr int kKeypointSetWidth = 1 + 3 * kKeypointSetSize;

std::vector<double> keypointSetBlock(const std::vector<Eigen::Vector3f>& keypoints);

}  // namespace keyturn::learning
