#include "keyturn/core/plugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

#include "keyturn/core/error.h"
#include "keyturn/core/install_layout.h"

namespace keyturn {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> searchFolders() {
  std::vector<fs::path> folders;
  if (const char* env = std::getenv("KEYTURN_PLUGIN_PATH")) {
    std::string list = env;
    for (std::size_t start = 0; start <= list.size();) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      if (end > start) folders.emplace_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  const fs::path own = runningFile();
  if (!own.empty()) {
    folders.push_back(own.parent_path());  // a Python module carries its plugins beside it
    folders.push_back(prefixPath("lib/keyturn"));
  }
  return folders;
}

void* openPlugin(const std::string& name) {
  const fs::path path = pluginFile("libkeyturn_" + name + ".so", "plugin '" + name + "'");
  if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) return handle;
  const char* why = dlerror();
  throw InstallError("plugin '" + name + "' (" + path.string() + ") cannot be loaded: " + (why ? why : "unknown reason"));
}

}  // namespace

fs::path pluginFile(const std::string& file, const std::string& what) {
  std::string searched;
  for (const fs::path& folder : searchFolders()) {
    const fs::path path = folder / file;
    std::error_code ec;
    if (fs::exists(path, ec)) return path;
    searched += (searched.empty() ? "" : ", ") + folder.string();
  }
  throw InstallError(what + " (" + file + ") not found in " + (searched.empty() ? "no folder" : searched) +
              " (set KEYTURN_PLUGIN_PATH to the folder that holds it)");
}

void* pluginSymbol(const std::string& name, const char* symbol) {
  static std::mutex mutex;
  static std::map<std::string, void*> handles;
  std::lock_guard<std::mutex> lock(mutex);
  void*& handle = handles[name];
  if (!handle) handle = openPlugin(name);
  dlerror();
  void* address = dlsym(handle, symbol);
  if (!address) {
    const char* why = dlerror();
    throw InstallError("plugin '" + name + "' has no entry point '" + symbol + "'" + (why ? std::string(": ") + why : ""));
  }
  return address;
}

}  // namespace keyturn
