#include "keyturn/core/camera_file.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "keyturn/core/error.h"
#include "keyturn/core/json_error.h"
#include "keyturn/core/json_file.h"
#include "file_error.h"

namespace fs = std::filesystem;

namespace keyturn {
namespace {

using detail::fail;  // "PATH: what", printable

std::string readAll(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail(path, "is a directory, expected a camera file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, fs::exists(path, ec) ? "cannot read" : "no such file");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string count(std::size_t n) { return std::to_string(n) + (n == 1 ? " value" : " values"); }

double number(const std::string& path, const std::string& key, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v)) fail(path, key + " is '" + text + "', not a number");
  return v;
}

// ---- what every format comes down to: a 3 × 3 camera matrix and distortion coefficients ----

struct CameraModel {
  std::vector<double> matrix;  // row-major, 9 values once checked
  std::string matrix_name;     // as the file calls it, for errors
  std::vector<double> distortion;
  std::string distortion_name, distortion_model;  // model "" when the file names none (OpenCV)
};

LensDistortion lensDistortion(const std::string& path, const CameraModel& c) {
  LensDistortion d;
  const std::vector<double>& k = c.distortion;
  bool zero = true;
  for (double v : k) zero = zero && v == 0;
  if (zero) return d;  // whatever the model is called, it changes nothing
  std::string model = c.distortion_model;
  if (model.empty()) model = k.size() == 4 || k.size() == 5 ? "plumb_bob" : k.size() == 8 ? "rational_polynomial" : "";
  const bool radial_tangential = model == "plumb_bob" || model == "radtan" || model == "radial-tangential";
  if (model.empty())
    fail(path, c.distortion_name + " holds " + count(k.size()) +
                   ": keyturn applies plumb_bob (k1 k2 p1 p2 [k3]) or rational_polynomial (8) distortion");
  if (!radial_tangential && model != "rational_polynomial")
    fail(path, "distortion model '" + model +
                   "' with non-zero coefficients: keyturn applies plumb_bob and rational_polynomial only");
  if (radial_tangential && k.size() != 4 && k.size() != 5)
    fail(path, c.distortion_name + " holds " + count(k.size()) + ", " + model + " has 4 or 5 (k1 k2 p1 p2 [k3])");
  if (!radial_tangential && k.size() != 8)
    fail(path, c.distortion_name + " holds " + count(k.size()) + ", rational_polynomial has 8 (k1 k2 p1 p2 k3 k4 k5 k6)");
  d.k1 = k[0], d.k2 = k[1], d.p1 = k[2], d.p2 = k[3];
  if (k.size() > 4) d.k3 = k[4];
  if (k.size() == 8) d.k4 = k[5], d.k5 = k[6], d.k6 = k[7];
  return d;
}

DepthIntrinsics intrinsicsOf(const std::string& path, const CameraModel& c, const char* layout) {
  const std::vector<double>& m = c.matrix;
  if (m.size() != 9) fail(path, c.matrix_name + " holds " + count(m.size()) + ", a camera matrix has 9 (3 × 3)");
  if (m[6] != 0 || m[7] != 0 || m[8] != 1)
    fail(path, c.matrix_name + " is not a pinhole camera matrix (its last row is not 0 0 1; " + layout + ")");
  if (m[1] != 0 || m[3] != 0) fail(path, c.matrix_name + " has skew or rotation (fx 0 cx / 0 fy cy / 0 0 1 expected)");
  DepthIntrinsics k{m[0], m[4], m[2], m[5]};
  if (!(k.fx > 0) || !(k.fy > 0)) fail(path, "fx and fy must be positive (" + c.matrix_name + " has fx " +
                                                 std::to_string(k.fx) + ", fy " + std::to_string(k.fy) + ")");
  k.distortion = lensDistortion(path, c);
  return k;
}

// keyturn's own keys: fx, fy, cx, cy (pixels) and an optional depth_scale (metres per unit).
DepthImageOptions fromFlatKeys(const std::string& path, const std::vector<std::pair<std::string, std::string>>& entries) {
  DepthImageOptions out;
  DepthIntrinsics k;
  bool seen[4] = {false, false, false, false};
  const char* names[4] = {"fx", "fy", "cx", "cy"};
  double* fields[4] = {&k.fx, &k.fy, &k.cx, &k.cy};
  for (const auto& [key, value] : entries) {
    for (int i = 0; i < 4; ++i)
      if (key == names[i]) {
        *fields[i] = number(path, key, value);
        seen[i] = true;
      }
    if (key == "depth_scale") out.depth_scale = number(path, key, value);
  }
  for (int i = 0; i < 4; ++i)
    if (!seen[i])
      fail(path, std::string("no ") + names[i] +
                     " (a camera file holds fx, fy, cx, cy in pixels, or a camera matrix as ROS, OpenCV and Open3D write it)");
  if (!(k.fx > 0) || !(k.fy > 0)) fail(path, "fx and fy must be positive");
  if (!(out.depth_scale > 0)) fail(path, "depth_scale must be positive");
  out.intrinsics = k;
  return out;
}

// ---- JSON: keyturn's flat keys or Open3D's PinholeCameraIntrinsic ----

std::string jsonText(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  std::ostringstream s;
  s.precision(17);
  if (v.is_number()) s << v.get<double>();
  else s << v.dump();
  return s.str();
}

DepthImageOptions fromJson(const std::string& path, const std::string& text) {
  const nlohmann::json j = parseJson(text, path, JsonShape::Object);
  if (j.contains("intrinsic_matrix")) {  // Open3D: o3d.io.write_pinhole_camera_intrinsic
    const nlohmann::json& m = j["intrinsic_matrix"];
    if (!m.is_array()) fail(path, "intrinsic_matrix is not a list of 9 numbers");
    CameraModel c;
    c.matrix_name = "intrinsic_matrix";
    std::vector<double> column_major;
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (!m[i].is_number()) fail(path, "intrinsic_matrix[" + std::to_string(i) + "] is '" + jsonText(m[i]) + "', not a number");
      column_major.push_back(m[i].get<double>());
    }
    c.matrix = column_major;
    if (column_major.size() == 9)  // Eigen's storage order: fx 0 0  0 fy 0  cx cy 1
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) c.matrix[r * 3 + col] = column_major[col * 3 + r];
    DepthImageOptions out;
    out.intrinsics = intrinsicsOf(path, c, "Open3D stores it column-major: fx 0 0 0 fy 0 cx cy 1");
    return out;
  }
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& [k, v] : j.items())
    if (v.is_number() || v.is_string()) entries.emplace_back(k, jsonText(v));
  return fromFlatKeys(path, entries);
}

// ---- YAML: keyturn's flat keys, ROS camera_info, a CameraInfo message, OpenCV's FileStorage ----

std::vector<double> yamlNumbers(const std::string& path, const YAML::Node& n, const std::string& name) {
  if (!n.IsSequence()) fail(path, name + " is not a list of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string at = name + "[" + std::to_string(i) + "]";
    if (!n[i].IsScalar()) fail(path, at + " is not a number");
    out.push_back(number(path, at, n[i].Scalar()));
  }
  return out;
}

// {rows, cols, data} as camera_calibration_parsers and cv::FileStorage (!!opencv-matrix) write it.
std::vector<double> yamlMatrix(const std::string& path, const YAML::Node& n, const std::string& name) {
  if (!n.IsMap() || !n["data"]) fail(path, name + " has no data (expected rows, cols and data)");
  std::vector<double> data = yamlNumbers(path, n["data"], name + ".data");
  if (n["rows"] && n["cols"]) {
    const auto dim = [&](const char* key) {
      const YAML::Node v = n[key];
      return v.IsScalar() ? number(path, name + "." + key, v.Scalar()) : -1.0;
    };
    const double rows = dim("rows"), cols = dim("cols");
    if (rows * cols != static_cast<double>(data.size()))
      fail(path, name + " is " + jsonText(rows) + " × " + jsonText(cols) + " but its data holds " + count(data.size()));
  }
  return data;
}

std::string yamlScalar(const YAML::Node& map, const char* key) {
  const YAML::Node v = map[key];
  return v && v.IsScalar() ? v.Scalar() : std::string();
}

// The first of `keys` the map has (ROS 1 writes K, ROS 2 k).
YAML::Node firstOf(const YAML::Node& map, std::initializer_list<const char*> keys, std::string* found) {
  for (const char* k : keys)
    if (map[k]) {
      *found = k;
      return map[k];
    }
  return YAML::Node();
}

DepthImageOptions fromYaml(const std::string& path, std::string text) {
  // cv::FileStorage starts its files with "%YAML:1.0", which is not a YAML directive (YAML spells it
  // "%YAML 1.0" and yaml-cpp reads only 1.x): the line is dropped rather than relying on how a given
  // yaml-cpp treats an unknown directive. Its "!!opencv-matrix" tags need nothing: yaml-cpp keeps
  // an unknown tag on the node and reads the mapping under it as any other.
  if (text.rfind("%YAML:", 0) == 0) text.erase(0, text.find('\n'));
  const YAML::Node root = [&] {  // const: looking a key up in a non-const node may add it
    try {
      return YAML::Load(text);
    } catch (const YAML::Exception& e) {
      fail(path, "neither JSON nor valid YAML (line " + std::to_string(e.mark.line + 1) + ", column " +
                     std::to_string(e.mark.column + 1) + ": " + e.msg + ")");
    }
  }();
  if (!root.IsMap())
    fail(path, "not a camera file: expected JSON or YAML keys (fx, fy, cx, cy, or a camera matrix as ROS, OpenCV and Open3D write it)");

  CameraModel c;
  std::string key;
  if (root["camera_matrix"]) {  // ROS camera_calibration_parsers, or OpenCV's FileStorage
    c.matrix_name = "camera_matrix";
    c.matrix = yamlMatrix(path, root["camera_matrix"], c.matrix_name);
    const YAML::Node d = firstOf(root, {"distortion_coefficients", "dist_coeffs", "distortion_coeffs"}, &key);
    if (d) c.distortion = yamlMatrix(path, d, key);
    c.distortion_name = key;
    c.distortion_model = yamlScalar(root, "distortion_model");
  } else if (const YAML::Node m = firstOf(root, {"K", "k"}, &key); m && m.IsSequence()) {  // sensor_msgs/CameraInfo
    c.matrix_name = key;
    c.matrix = yamlNumbers(path, m, key);
    const YAML::Node d = firstOf(root, {"D", "d"}, &key);
    if (d) c.distortion = yamlNumbers(path, d, key);
    c.distortion_name = key;
    c.distortion_model = yamlScalar(root, "distortion_model");
  } else {
    std::vector<std::pair<std::string, std::string>> entries;
    for (const auto& kv : root)
      if (kv.first.IsScalar()) {
        if (!kv.second.IsScalar()) continue;
        entries.emplace_back(kv.first.Scalar(), kv.second.Scalar());
      }
    return fromFlatKeys(path, entries);
  }
  DepthImageOptions out;
  out.intrinsics = intrinsicsOf(path, c, "row-major: fx 0 cx 0 fy cy 0 0 1");
  return out;
}

}  // namespace

DepthImageOptions readCameraFile(const std::string& path) {
  const std::string text = readAll(path);
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) fail(path, "empty camera file");
  if (text.find('\0') != std::string::npos) fail(path, "a binary file, not a camera file (JSON or YAML)");
  return text[first] == '{' ? fromJson(path, text) : fromYaml(path, text);
}

}  // namespace keyturn
