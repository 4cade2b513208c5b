#include "layout_walk.h"

#include <algorithm>
#include <filesystem>

#include "keyturn/core/error.h"

namespace fs = std::filesystem;

namespace keyturn::dataset {

std::vector<LayoutFile> layoutFiles(const std::string& source, std::vector<std::string>& problems) {
  std::error_code ec;
  if (!fs::is_directory(source, ec)) throw Error(source + ": not a folder");
  std::vector<LayoutFile> out;
  fs::recursive_directory_iterator it(source, fs::directory_options::skip_permission_denied, ec), end;
  if (ec) throw Error(source + ": cannot list folder: " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) {
      problems.push_back(source + ": cannot list a folder: " + ec.message());
      break;
    }
    const std::string name = it->path().filename().string();
    if (!name.empty() && name[0] == '.') {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    LayoutFile f;
    f.path = it->path().string();
    for (const auto& p : fs::relative(it->path(), source, ec)) f.parts.push_back(p.string());
    out.push_back(std::move(f));
  }
  std::sort(out.begin(), out.end(), [](const LayoutFile& a, const LayoutFile& b) { return a.path < b.path; });
  return out;
}

}  // namespace keyturn::dataset
