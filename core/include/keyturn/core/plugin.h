#pragma once
// Plugins: the heavy libraries (libtorch for the network, Qt for report plots, OpenCV's image
// codecs) sit in shared modules loaded on first use, so a process loads only what its work needs:
// `keyturn --help` or a describe of a PCD view loads none of them (docs/benchmarks.md, start-up).
//
// A plugin NAME is the module libkeyturn_NAME.so, looked for in this order:
//   1. the folders in KEYTURN_PLUGIN_PATH (colon-separated), when set;
//   2. the folder of the program or module that holds this code (a Python package keeps its
//      plugins beside its extension), and its ../lib/keyturn (an install: bin/ and lib/keyturn/);
//   3. the build tree's lib/keyturn (for programs run from the build, such as the tests).
// Loaded once per process and never unloaded; thread-safe.
#include <filesystem>
#include <string>

#include "keyturn/core/error.h"

namespace keyturn {

// keyturn's own installation is incomplete: a plugin or the worker program missing or not loadable.
// A property of the machine, not of any input: code that records an error per view (a feature
// cache's rows) lets this one through, so a run with a broken install stops instead of caching
// every view as failed for the runs after it.
class InstallError : public Error {
 public:
  using Error::Error;
};

// The address of `symbol` in plugin `name`. Throws InstallError naming the plugin, the folders
// searched and the loader's reason when the module or the symbol cannot be found.
void* pluginSymbol(const std::string& name, const char* symbol);

// The path of `file` in the first of the folders above that holds it (plugins, and the worker
// program of worker_process.h). Throws InstallError naming `what`, the file and the folders searched.
std::filesystem::path pluginFile(const std::string& file, const std::string& what);

template <class Function>
Function* pluginFunction(const std::string& name, const char* symbol) {
  return reinterpret_cast<Function*>(pluginSymbol(name, symbol));
}

}  // namespace keyturn

// Marks a plugin's entry points (the modules are built with hidden visibility).
#define KEYTURN_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))
