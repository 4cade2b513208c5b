#pragma once
// The turntable's axis from a dataset's sphere-target sequence (keyturn
// calibrate-axis): the target found in each view (core/axis_calibration.h), the
// axis fitted, and refused when the sequence cannot have been a target's (a
// fixed ball off the axis must go round on a circle, at the reported angles).
// Written as a keyturn-axis-calibration file, as sidecars.h reads it.
#include <functional>
#include <string>

#include "keyturn/core/axis_calibration.h"

namespace keyturn::rig {

struct AxisSequence {
  std::string dataset;
  std::string cls, instance, elevation;  // empty: any
};

struct DatasetAxisCalibration {
  AxisCalibration axis;
  double sphere_radius = 0;  // the target's mean fitted radius (m)
  std::string source;        // the dataset
};

// skipped: a view in which the target was not found, and why. view_done: with 0 before the first
// view, then after each.
// Throws keyturn::Error naming the dataset for fewer than 3 views or targets, or a sequence
// that is not a sphere target's.
DatasetAxisCalibration calibrateAxisFromDataset(const AxisSequence& sequence,
                                                const std::function<void(const std::string& pcd, const std::string& why)>& skipped,
                                                const std::function<void(std::size_t done, std::size_t views)>& view_done);

// Durably.
void writeAxisCalibration(const std::string& path, const DatasetAxisCalibration& calibration);

}  // namespace keyturn::rig
