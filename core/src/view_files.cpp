#include "keyturn/core/view_files.h"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace keyturn {

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool isViewFile(const fs::path& p, bool depth_images) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".png") return depth_images && !isCompanionImage(p.filename().string());
  return ext == ".pcd" || ext == ".ply";
}

}  // namespace

bool isCompanionImage(const std::string& name) {
  for (const char* s : {"_mask.png", "_maskcrop.png", "_crop.png", "_rgb.png", kDistanceImageSuffix,
                        kAmplitudeImageSuffix, kConfidenceImageSuffix})
    if (endsWith(name, s)) return true;
  return false;
}

ViewFileList collectViewFiles(const std::vector<std::string>& inputs, bool depth_images) {
  ViewFileList out;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (fs::recursive_directory_iterator it(in, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec) && isViewFile(it->path(), depth_images)) found.push_back(it->path().string());
      if (ec) out.errors.push_back(in + ": cannot list folder: " + ec.message());
      std::sort(found.begin(), found.end());
      if (found.empty() && !ec) out.errors.push_back(in + (depth_images ? ": folder holds no .pcd, .ply or depth .png files"
                                                                             : ": folder holds no .pcd or .ply files"));
      out.files.insert(out.files.end(), found.begin(), found.end());
    } else if (fs::exists(in, ec)) {
      out.files.push_back(in);
    } else {
      out.errors.push_back(in + ": no such file or folder");
    }
  }
  return out;
}

}  // namespace keyturn
