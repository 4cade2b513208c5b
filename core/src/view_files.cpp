#include "keyturn/core/view_files.h"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace keyturn {

namespace {
bool isViewFile(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".pcd" || ext == ".ply";
}
}  // namespace

ViewFileList collectViewFiles(const std::vector<std::string>& inputs) {
  ViewFileList out;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (fs::recursive_directory_iterator it(in, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec) && isViewFile(it->path())) found.push_back(it->path().string());
      if (ec) out.errors.push_back(in + ": cannot list folder: " + ec.message());
      std::sort(found.begin(), found.end());
      if (found.empty() && !ec) out.errors.push_back(in + ": folder holds no .pcd or .ply files");
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
