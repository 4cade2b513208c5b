#include "keyturn/drivers/mesasr_library.h"

#include <dlfcn.h>

#include <cstdlib>

#include "keyturn/core/error.h"

namespace keyturn::drivers {

MesaSrLibrary::~MesaSrLibrary() {
  if (handle) ::dlclose(handle);
}

std::vector<std::string> MesaSrLibrary::defaultNames() {
  return {"libmesasr.so", "libmesasr.so.1", "libmesasr.so.0"};
}

std::shared_ptr<MesaSrLibrary> MesaSrLibrary::load(const std::string& explicit_path) {
  std::vector<std::string> candidates;
  if (!explicit_path.empty()) candidates.push_back(explicit_path);
  else if (const char* env = std::getenv("KEYTURN_MESASR_LIB"); env && *env) candidates.push_back(env);
  else candidates = defaultNames();

  auto lib = std::make_shared<MesaSrLibrary>();
  std::string tried, last_error;
  for (const auto& name : candidates) {
    // NODELETE: a camera library may leave worker threads behind (the simulator's
    // Embree pool does); unmapping its code under them would crash at exit.
    lib->handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (lib->handle) {
      lib->path = name;
      break;
    }
    tried += (tried.empty() ? "" : ", ") + name;
    if (const char* e = ::dlerror()) last_error = e;
  }
  if (!lib->handle)
    throw Error("libMesaSR not found (tried " + tried + (last_error.empty() ? "" : ": " + last_error) +
                "); install MESA's libmesasr, set KEYTURN_MESASR_LIB to its path, or use the simulated camera (sim)");

  std::string missing;
#define KEYTURN_MESASR_RESOLVE(ret, name, args)                                        \
  lib->name = reinterpret_cast<ret(*) args>(::dlsym(lib->handle, #name));             \
  if (!lib->name) missing += std::string(missing.empty() ? "" : ", ") + #name;
  KEYTURN_MESASR_FUNCTIONS(KEYTURN_MESASR_RESOLVE)
#undef KEYTURN_MESASR_RESOLVE
  // Only what keyturn calls must be there; dialogs and raw TCP are optional.
  const bool essential = lib->SR_OpenUSB && lib->SR_OpenETH && lib->SR_Close && lib->SR_Acquire &&
                         lib->SR_GetImageList && lib->SR_SetMode && lib->SR_CoordTrfFlt &&
                         lib->SR_GetRows && lib->SR_GetCols;
  if (!essential)
    throw Error(lib->path + ": not a usable libMesaSR (missing " + missing + ")");
  lib->KTSIM_OpenWithConfig = reinterpret_cast<KTSIM_OpenWithConfigFn*>(::dlsym(lib->handle, "KTSIM_OpenWithConfig"));
  return lib;
}

}  // namespace keyturn::drivers
