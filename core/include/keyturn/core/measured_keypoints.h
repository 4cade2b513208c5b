#pragma once
// ISS run on the measured points at the chain's scale (describe --keypoint-placement measured;
// issue 49). The working resolution's voxel means move and appear or vanish when the sensor's noise
// moves a point across a voxel's face, and ISS re-decides on them; here the scatter matrices and
// the suppression are taken over the measured points themselves, with the radii of the working
// resolution, so each keypoint is a measured point and a small jitter moves each neighbourhood by
// as little as it moves the points. The working resolution stays the graph's: each keypoint's
// geodesics start at the working vertex nearest it.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/iss.h"

namespace keyturn {

struct MeasuredKeypoints {
  std::vector<Eigen::Vector3f> positions;  // measured points, ascending measured index
  std::vector<int> vertex;                  // per keypoint, a distinct vertex of the working view
  std::vector<double> weight;               // as IssResult::weight (a weighted budget), else empty
  int filled = 0;                           // as IssResult::filled
};

// ISS (iss.h, radii in multiples of working_resolution) over `measured`; each keypoint is then
// given the nearest vertex of `working` no earlier keypoint took (more keypoints than vertices:
// the rest are dropped). Deterministic.
MeasuredKeypoints detectKeypointsOnMeasuredPoints(const PointSet& measured, const PointSet& working,
                                                  double working_resolution, const IssOptions& iss);

}  // namespace keyturn
