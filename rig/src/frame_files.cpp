#include "keyturn/rig/frame_files.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/error.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/view_files.h"

namespace fs = std::filesystem;

namespace keyturn::rig {
namespace {

// Empty when the file is not there; the image when it is, on the cloud's grid.
std::vector<std::uint16_t> readPng16(const std::string& path, std::uint32_t w, std::uint32_t h) {
  if (!fs::exists(path)) return {};
  return loadPng16(path, w, h);
}

std::uint16_t clampRaw(double v) { return static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0, 65535.0))); }

}  // namespace

drivers::TofFrame readFrameFiles(const std::string& pcd_path, double range_m) {
  std::string base = pcd_path;
  if (base.size() > 4 && base.substr(base.size() - 4) == ".pcd") base.resize(base.size() - 4);
  else throw Error(pcd_path + ": a frame is read from a .pcd file");
  drivers::TofFrame f;
  f.cloud = loadCloud(pcd_path);
  f.width = f.cloud.width;
  f.height = f.cloud.height;
  const std::size_t n = f.cloud.size();
  f.distance = readPng16(base + kDistanceImageSuffix, f.width, f.height);
  f.amplitude = readPng16(base + kAmplitudeImageSuffix, f.width, f.height);
  f.confidence = readPng16(base + kConfidenceImageSuffix, f.width, f.height);
  if (f.distance.empty() && range_m > 0) {
    f.distance.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = f.cloud.points[i];
      // A return is never 0 (0 means none), however close.
      f.distance[i] = Cloud::isValid(p) ? std::max<std::uint16_t>(1, clampRaw(p.norm() / range_m * 65535.0)) : 0;
    }
  }
  if (f.amplitude.empty() && f.cloud.amplitude.size() == n) {
    f.amplitude.resize(n);
    for (std::size_t i = 0; i < n; ++i) f.amplitude[i] = clampRaw(f.cloud.amplitude[i]);
  }
  if (f.confidence.empty() && f.cloud.confidence.size() == n) {
    f.confidence.resize(n);
    for (std::size_t i = 0; i < n; ++i) f.confidence[i] = clampRaw(f.cloud.confidence[i] * 65535.0);
  }
  return f;
}

std::vector<std::string> writeFrameFiles(const std::string& pcd_path, const drivers::TofFrame& f) {
  std::string base = pcd_path;
  if (base.size() > 4 && base.substr(base.size() - 4) == ".pcd") base.resize(base.size() - 4);
  else throw Error(pcd_path + ": the view must be written as a .pcd file");
  std::vector<std::string> written;
  saveCloud(pcd_path, f.cloud, PcdEncoding::BinaryCompressed);
  written.push_back(pcd_path);
  const struct {
    const char* suffix;
    const std::vector<std::uint16_t>* img;
  } images[] = {{kDistanceImageSuffix, &f.distance}, {kAmplitudeImageSuffix, &f.amplitude}, {kConfidenceImageSuffix, &f.confidence}};
  for (const auto& im : images) {
    if (im.img->size() != static_cast<std::size_t>(f.width) * f.height) continue;  // e.g. no confidence map
    savePng16(base + im.suffix, *im.img, f.width, f.height);
    written.push_back(base + im.suffix);
  }
  return written;
}

}  // namespace keyturn::rig
