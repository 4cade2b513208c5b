#pragma once
// Reading the small JSON files a dataset carries: a view's sidecar and the
// axis calibration. Every malformed file is one keyturn::Error naming it.
#include <Eigen/Core>
#include <optional>
#include <string>

#include "keyturn/dataset/dataset.h"

namespace keyturn::dataset {

// The sidecar's camera ← turntable transform; nullopt when the rig was not calibrated.
std::optional<Eigen::Matrix4d> readViewTransform(const std::string& sidecar_path);

// The camera a view was taken with, as its sidecar records it (device string, serial, and the
// settings it keeps: modulation, integration time, auto exposure, amplitude threshold, acquire mode;
// rig::readViewCamera makes them a camera's settings). A view imported from another tool (keyturn
// import) records none: every field empty, and imported set.
struct SidecarCameraRecord {
  SidecarCamera camera;
  bool imported = false;  // its captured_at is when it was imported, not taken
};
SidecarCameraRecord readSidecarCamera(const std::string& sidecar_path);

// A keyturn-axis-calibration file's camera ← turntable at 0°.
Eigen::Matrix4d readAxisCalibration(const std::string& path);

// A capture's axis calibration: reads it (as above) and keeps a copy with the
// dataset as DATASET/calibration.json (written durably). Returns camera ← turntable at 0°.
Eigen::Matrix4d adoptAxisCalibration(const std::string& path, const std::string& dataset_root);

}  // namespace keyturn::dataset
