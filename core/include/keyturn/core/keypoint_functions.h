#pragma once
// Euclidean keypoint functions over ALL pairs and triples of keypoints (§4.4):
// no random sampling, so the result depends only on the keypoint set.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/histogram.h"

namespace keyturn {

// KPD2: |a - b| for every unordered pair. K(K-1)/2 values.
std::vector<float> keypointDistances(const std::vector<Eigen::Vector3f>& kp);
// KPD3: sqrt(area) of the triangle of every unordered triple. K(K-1)(K-2)/6 values.
std::vector<float> keypointSqrtAreas(const std::vector<Eigen::Vector3f>& kp);
// KPA3: every interior angle (radians) of every unordered triple, i.e. the angle
// at each of its three vertices, so no vertex is privileged by keypoint order.
// Degenerate triangles (a zero-length side) contribute nothing. Up to 3·C(K,3) values.
std::vector<float> keypointAngles(const std::vector<Eigen::Vector3f>& kp);
// KPA3's PDF: histogramPdf(keypointAngles(kp), bins, range), the same numbers, with an arccos
// only where a cheap bound cannot tell an angle's bin (within 1e-4 rad of a bin edge: ~0.2 % of
// the angles at 32 bins); the rest are binned from a polynomial arccos good to 6.7e-5 rad.
// With linear binning each angle is shared between two bins by the polynomial arccos alone (its
// 6.7e-5 rad error moves under 0.1 % of an angle's weight at 32 bins).
// weights, when given (one per keypoint), weigh each triangle's angles by the product of its
// corners' weights (the weighted budget, iss.h); such a PDF is binned from the polynomial arccos.
std::vector<double> keypointAnglePdf(const std::vector<Eigen::Vector3f>& kp, int bins, HistogramRange range,
                                     Binning binning = Binning::Hard, const std::vector<double>* weights = nullptr);

// The weight of each pair (w_a·w_b) and triple (w_a·w_b·w_c), in the order keypointDistances and
// keypointSqrtAreas list their values.
std::vector<float> pairWeights(const std::vector<double>& keypoint_weights);
std::vector<float> tripleWeights(const std::vector<double>& keypoint_weights);

}  // namespace keyturn
