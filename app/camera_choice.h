#pragma once
// --camera sim|usb[:SERIAL]|eth:IP → an open TofCamera. "sim" loads
// libmesasr-sim (the build's, or $KEYTURN_MESASR_SIM) and opens its first USB
// camera; the others load MESA's libMesaSR ($KEYTURN_MESASR_LIB or the usual sonames).
#include <memory>
#include <string>

#include "keyturn/drivers/tof_camera.h"

namespace keyturn::app {

// library: libMesaSR path for usb/eth (empty: $KEYTURN_MESASR_LIB or the usual sonames).
std::unique_ptr<drivers::TofCamera> openCamera(const std::string& spec, const std::string& sim_config,
                                               const std::string& library = "");
std::string simulatorLibraryPath();

}  // namespace keyturn::app
