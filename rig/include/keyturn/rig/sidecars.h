#pragma once
// Reading the small JSON files a dataset carries: a view's sidecar and the
// axis calibration. Every malformed file is one keyturn::Error naming it.
#include <Eigen/Core>
#include <optional>
#include <string>

namespace keyturn::rig {

// The sidecar's camera ← turntable transform; nullopt when the rig was not calibrated.
std::optional<Eigen::Matrix4d> readViewTransform(const std::string& sidecar_path);

// A keyturn-axis-calibration file's camera ← turntable at 0°.
Eigen::Matrix4d readAxisCalibration(const std::string& path);

}  // namespace keyturn::rig
