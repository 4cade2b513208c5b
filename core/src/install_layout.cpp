#include "keyturn/core/install_layout.h"

#include <dlfcn.h>
#include <link.h>

#include <cstdlib>

#include "keyturn/core/error.h"

namespace keyturn {

namespace fs = std::filesystem;

fs::path runningFile() {
  Dl_info info{};
  link_map* map = nullptr;
  if (dladdr1(reinterpret_cast<void*>(&runningFile), &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) &&
      map && map->l_name && map->l_name[0] != '\0')
    return map->l_name;
  std::error_code ec;  // the main program: its link-map name is empty
  return fs::read_symlink("/proc/self/exe", ec);
}

fs::path prefixPath(const fs::path& relative) {
  const fs::path own = runningFile();
  if (own.empty()) return {};
  return own.parent_path().parent_path() / relative;
}

fs::path dataDirectory() {
  if (const char* env = std::getenv("KEYTURN_DATA_DIR"); env && *env) {
    std::error_code ec;
    if (!fs::is_directory(env, ec)) throw Error(std::string("KEYTURN_DATA_DIR=") + env + ": not a folder");
    return env;
  }
  const fs::path dir = prefixPath("share/keyturn");
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec))
    throw Error("keyturn's data folder " + (dir.empty() ? std::string("share/keyturn") : dir.string()) +
                " not found beside " + runningFile().string() + " (set KEYTURN_DATA_DIR to the folder holding objects/ and models/)");
  // The build tree's share/keyturn is a link to data/: name the real folder.
  const fs::path real = fs::canonical(dir, ec);
  return ec ? dir : real;
}

}  // namespace keyturn
