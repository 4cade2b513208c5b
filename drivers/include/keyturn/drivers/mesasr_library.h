#pragma once
// libMesaSR loaded at run time (dlopen), so keyturn builds and runs without it.
// Chosen by: an explicit path, else $KEYTURN_MESASR_LIB, else the usual sonames
// through the dynamic loader's search path (LD_LIBRARY_PATH, ld.so.cache).
#include <memory>
#include <string>
#include <vector>

#include "keyturn/drivers/mesasr_api.h"

namespace keyturn::drivers {

struct MesaSrLibrary {
#define KEYTURN_MESASR_POINTER(ret, name, args) ret(*name) args = nullptr;
  KEYTURN_MESASR_FUNCTIONS(KEYTURN_MESASR_POINTER)
#undef KEYTURN_MESASR_POINTER
  // keyturn's extension (mesasr_api.h): present in libmesasr-sim only, else null.
  KTSIM_OpenWithConfigFn* KTSIM_OpenWithConfig = nullptr;

  std::string path;  // what was loaded
  void* handle = nullptr;
  ~MesaSrLibrary();

  // Throws keyturn::Error with one line naming what was tried and what is missing.
  static std::shared_ptr<MesaSrLibrary> load(const std::string& path = "");
  static std::vector<std::string> defaultNames();
};

}  // namespace keyturn::drivers
