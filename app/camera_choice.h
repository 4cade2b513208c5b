#pragma once
// --camera sim|usb[:SERIAL]|eth:IP → an open TofCamera. "sim" loads
// libmesasr-sim (the build's, or $KEYTURN_MESASR_SIM) and opens its first USB
// camera; the others load MESA's libMesaSR ($KEYTURN_MESASR_LIB or the usual sonames).
#include <functional>
#include <memory>
#include <string>

#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/drivers/tof_camera.h"

namespace keyturn::app {

// library: libMesaSR path for usb/eth (empty: $KEYTURN_MESASR_LIB or the usual sonames).
// log: the driver's retries and reconnects (default: stderr).
std::unique_ptr<drivers::TofCamera> openCamera(const std::string& spec, const std::string& sim_config,
                                               const std::string& library = "",
                                               std::function<void(const std::string&)> log = {});
std::string simulatorLibraryPath();
// A real camera's spec (usb, usb:SERIAL, eth:IP); anything else is refused naming every choice, sim included.
drivers::Sr4000Connection parseCameraSpec(const std::string& spec);

}  // namespace keyturn::app
