#include "keyturn/studio/studio_runtime_folder.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace keyturn::studio {
namespace {

constexpr const char* kPrefix = "keyturn-studio-";

}  // namespace

StudioRuntimeFolder::StudioRuntimeFolder()
    : path_((fs::temp_directory_path() / (kPrefix + std::to_string(::getpid()))).string()) {
  // Another studio may hold this folder for a moment: it is sweeping a folder its dead owner left
  // under this pid. It renames the folder away before it lets go, so the next try makes a new one.
  for (int attempt = 0;; ++attempt) {
    try {
      lock_.emplace(path_);
      break;
    } catch (const dataset::DatasetBusyError&) {
      if (attempt == 20) throw;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  removeAbandonedStudioFolders(fs::path(path_).parent_path().string());
}

StudioRuntimeFolder::~StudioRuntimeFolder() {
  lock_.reset();
  std::error_code ec;
  fs::remove_all(path_, ec);
}

int removeAbandonedStudioFolders(const std::string& temp) {
  // Listed first: the sweep renames what it removes, and must not meet those names again.
  std::vector<fs::path> folders;
  std::error_code ec;
  for (fs::directory_iterator it(temp, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind(kPrefix, 0) == 0 && it->is_directory(ec)) folders.push_back(it->path());
  int removed = 0;
  for (const fs::path& folder : folders) {
    try {
      // Taking the lock succeeds only when no running studio holds the folder.
      dataset::DatasetLock lock(folder.string());
      // Renamed while still locked, so a new studio given the dead one's pid never meets the folder
      // half removed: it finds the name free and makes its own.
      const fs::path trash = folder.string() + ".abandoned-" + std::to_string(::getpid());
      std::error_code rename_ec, remove_ec;
      fs::rename(folder, trash, rename_ec);
      fs::remove_all(rename_ec ? folder : trash, remove_ec);
      if (!remove_ec) ++removed;
    } catch (const Error&) {
      // Held by a running studio (or not ours to lock): leave it.
    }
  }
  return removed;
}

}  // namespace keyturn::studio
