#include "keyturn/dataset/sidecars.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "keyturn/core/error.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/json_file.h"
#include "keyturn/dataset/dataset_layout.h"

namespace keyturn::dataset {
namespace {

Eigen::Matrix4d matrix(const std::string& path, const nlohmann::json& j) {
  if (!j.is_array() || j.size() != 4) throw Error(path + ": camera_from_turntable must be a 4 × 4 array");
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    if (!j[r].is_array() || j[r].size() != 4) throw Error(path + ": camera_from_turntable must be a 4 × 4 array");
    for (int c = 0; c < 4; ++c) {
      if (!j[r][c].is_number()) throw Error(path + ": camera_from_turntable holds a non-number");
      m(r, c) = j[r][c].get<double>();
    }
  }
  if (!m.allFinite()) throw Error(path + ": camera_from_turntable holds a non-finite number");
  return m;
}

}  // namespace

std::optional<Eigen::Matrix4d> readViewTransform(const std::string& path) {
  const auto j = readJsonFile(path);
  if (!j.is_object() || !j.contains("camera_from_turntable")) throw Error(path + ": not a keyturn view sidecar");
  if (j["camera_from_turntable"].is_null()) return std::nullopt;
  return matrix(path, j["camera_from_turntable"]);
}

namespace {

// The key's value when the object has it; a value of another type throws (nlohmann's type_error).
template <typename T>
void readOptional(const nlohmann::json& c, const char* key, std::optional<T>& out) {
  if (c.contains(key)) out = c[key].get<T>();
}

}  // namespace

SidecarCameraRecord readSidecarCamera(const std::string& path) {
  const auto j = readJsonFile(path);
  if (!j.is_object()) throw Error(path + ": not a keyturn view sidecar");
  SidecarCameraRecord out;
  out.imported = j.contains("imported_by");
  if (!j.contains("camera")) return out;  // imported from another tool: no camera recorded
  const auto& c = j["camera"];
  if (!c.is_object()) throw Error(path + ": camera is not an object");
  try {
    SidecarCamera& cam = out.camera;
    cam.device = c.value("device", std::string());
    cam.serial = c.value("serial", std::uint32_t{0});
    readOptional(c, "modulation_mhz", cam.modulation_mhz);
    readOptional(c, "integration_time", cam.integration_time);
    readOptional(c, "auto_exposure", cam.auto_exposure);
    readOptional(c, "amplitude_threshold", cam.amplitude_threshold);
    readOptional(c, "acquire_mode", cam.acquire_mode);
  } catch (const std::exception& e) {
    throw Error(path + ": camera: " + e.what());
  }
  return out;
}

Eigen::Matrix4d readAxisCalibration(const std::string& path) {
  const auto j = readJsonFile(path);
  if (!j.is_object() || !j.contains("format") || !j["format"].is_string() ||
      j["format"].get<std::string>() != "keyturn-axis-calibration")
    throw Error(path + ": not a keyturn axis calibration");
  if (!j.contains("camera_from_turntable")) throw Error(path + ": no camera_from_turntable");
  return matrix(path, j["camera_from_turntable"]);
}

Eigen::Matrix4d adoptAxisCalibration(const std::string& path, const std::string& dataset_root) {
  const Eigen::Matrix4d m = readAxisCalibration(path);
  std::ifstream in(path, std::ios::binary);
  std::filesystem::create_directories(dataset_root);
  writeFileDurably(datasetPath(dataset_root, kCalibrationFile),
                   std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
  return m;
}

}  // namespace keyturn::dataset
