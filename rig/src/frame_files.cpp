#include "keyturn/rig/frame_files.h"

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/durable_file.h"

namespace fs = std::filesystem;

namespace keyturn::rig {
namespace {

void writePng16(const std::string& path, const std::vector<std::uint16_t>& img, std::uint32_t w, std::uint32_t h) {
  // OpenCV picks the encoder from the extension, so the temporary name keeps ".png".
  const std::string tmp = path.substr(0, path.size() - 4) + ".tmp.png";
  const cv::Mat m(static_cast<int>(h), static_cast<int>(w), CV_16UC1, const_cast<std::uint16_t*>(img.data()));
  bool ok = false;
  try {
    ok = cv::imwrite(tmp, m);
  } catch (const cv::Exception& e) {
    throw Error(path + ": PNG encoder failed: " + e.what());
  }
  if (!ok) throw Error(path + ": could not write PNG");
  commitFile(tmp, path);
}

}  // namespace

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
  } images[] = {{"_distance.png", &f.distance}, {"_amplitude.png", &f.amplitude}, {"_confidence.png", &f.confidence}};
  for (const auto& im : images) {
    if (im.img->size() != static_cast<std::size_t>(f.width) * f.height) continue;  // e.g. no confidence map
    writePng16(base + im.suffix, *im.img, f.width, f.height);
    written.push_back(base + im.suffix);
  }
  return written;
}

}  // namespace keyturn::rig
