#pragma once
// The working resolution: a view is described at a spacing set by its own size,
// not by the sensor, so that the chain's cost stays bounded at any density and one
// object seen by an SR4000 at 0.5 m and by a 640 x 480 sensor at 0.7 m gives
// keypoints of comparable count and place (docs/filtering.md has the rule).
#include <cstddef>

#include "keyturn/core/cloud.h"

namespace keyturn {

struct WorkingResolutionOptions {
  bool enabled = true;
  // Working spacing s = E / samples_across, E = 2 x the RMS distance of the points from their centroid.
  double samples_across = 40.0;
  // A view whose points already fall into at least this fraction of distinct s-voxels
  // is no denser than the working spacing and is kept as it is.
  double keep_fraction = 0.8;
};

struct WorkingResolutionReport {
  double extent = 0;   // E, metres
  double spacing = 0;  // s, metres
  bool subsampled = false;
  std::size_t before = 0, after = 0;
};

// Keeps, of the measured points nearest each s-voxel's centroid (measured points, not
// averages: keypoints stay on the sensor's surface), those at least s apart, in index
// order. The layout is kept: an organized view stays organized, the dropped pixels NaN.
void subsampleToWorkingResolution(Cloud& cloud, const WorkingResolutionOptions& options,
                                  WorkingResolutionReport* report = nullptr);

}  // namespace keyturn
