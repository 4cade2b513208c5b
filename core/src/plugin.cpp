#include "keyturn/core/plugin.h"

#include <dlfcn.h>
#include <link.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

#include "keyturn/core/error.h"

#ifndef KEYTURN_BUILD_PLUGIN_DIR
#define KEYTURN_BUILD_PLUGIN_DIR ""
#endif

namespace keyturn {
namespace {

namespace fs = std::filesystem;

// The file of the program or shared module this code was linked into.
fs::path ownFile() {
  Dl_info info{};
  link_map* map = nullptr;
  if (dladdr1(reinterpret_cast<void*>(&pluginSymbol), &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) &&
      map && map->l_name && map->l_name[0] != '\0')
    return map->l_name;
  std::error_code ec;  // the main program: its link-map name is empty
  return fs::read_symlink("/proc/self/exe", ec);
}

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
  const fs::path own = ownFile();
  if (!own.empty()) {
    folders.push_back(own.parent_path());
    folders.push_back(own.parent_path().parent_path() / "lib" / "keyturn");
  }
  if (KEYTURN_BUILD_PLUGIN_DIR[0] != '\0') folders.emplace_back(KEYTURN_BUILD_PLUGIN_DIR);
  return folders;
}

void* openPlugin(const std::string& name) {
  const std::string file = "libkeyturn_" + name + ".so";
  std::string searched;
  for (const fs::path& folder : searchFolders()) {
    const fs::path path = folder / file;
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      searched += (searched.empty() ? "" : ", ") + folder.string();
      continue;
    }
    if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) return handle;
    const char* why = dlerror();
    throw Error("plugin '" + name + "' (" + path.string() + ") cannot be loaded: " + (why ? why : "unknown reason"));
  }
  throw Error("plugin '" + name + "' (" + file + ") not found in " + (searched.empty() ? "no folder" : searched) +
              " (set KEYTURN_PLUGIN_PATH to the folder that holds it)");
}

}  // namespace

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
    throw Error("plugin '" + name + "' has no entry point '" + symbol + "'" + (why ? std::string(": ") + why : ""));
  }
  return address;
}

}  // namespace keyturn
