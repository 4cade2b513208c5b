#include "camera_choice.h"

#include <cstdlib>
#include <iostream>

#include "keyturn/drivers/sr4000_camera.h"

#ifndef KEYTURN_MESASR_SIM_DEFAULT
#define KEYTURN_MESASR_SIM_DEFAULT "libmesasr.so"
#endif

namespace keyturn::app {

std::string simulatorLibraryPath() {
  const char* env = std::getenv("KEYTURN_MESASR_SIM");
  return env && *env ? env : KEYTURN_MESASR_SIM_DEFAULT;
}

std::unique_ptr<drivers::TofCamera> openCamera(const std::string& spec, const std::string& sim_config,
                                               const std::string& library,
                                               std::function<void(const std::string&)> log) {
  drivers::Sr4000Options options;
  options.log = log ? std::move(log) : [](const std::string& line) { std::cerr << "keyturn: camera: " << line << "\n"; };
  if (spec == "sim") {
    if (!sim_config.empty()) ::setenv("MESASR_SIM_CONFIG", sim_config.c_str(), 1);
    return std::make_unique<drivers::Sr4000Camera>(drivers::MesaSrLibrary::load(simulatorLibraryPath()),
                                                   drivers::Sr4000Connection::parse("usb"), options);
  }
  const auto connection = drivers::Sr4000Connection::parse(spec);  // validate before loading
  return std::make_unique<drivers::Sr4000Camera>(drivers::MesaSrLibrary::load(library), connection, options);
}

}  // namespace keyturn::app
