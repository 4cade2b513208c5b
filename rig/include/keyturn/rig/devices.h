#pragma once
// Opening the rig's devices by name, for the CLI and the studio:
//   camera  sim|usb[:SERIAL]|eth:IP|playback:DATASET[@FPS] → a TofCamera. "sim" loads
//           libmesasr-sim (PREFIX/lib/keyturn/mesasr-sim, or $KEYTURN_MESASR_SIM) and opens its first USB
//           camera; usb and eth load MESA's libMesaSR ($KEYTURN_MESASR_LIB or the usual
//           sonames); playback replays a dataset (dataset_playback.h).
//   pose    modbus-tcp:HOST:PORT|modbus-rtu:DEV|can:IFACE → a PoseSource (for can:
//           the profile names the CANopen axes file). The simulated turntable is
//           opened with the simulated camera (simulated_rig.h).
#include <functional>
#include <memory>
#include <string>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/drivers/tof_camera.h"

namespace keyturn::rig {

using DeviceLog = std::function<void(const std::string&)>;

// library: libMesaSR path for usb/eth (empty: $KEYTURN_MESASR_LIB or the usual sonames).
// sim_config: for "sim", the simulator's configuration file ($MESASR_SIM_CONFIG is set to it;
// empty: left as it is). log: the driver's retries and reconnects (default: stderr).
std::unique_ptr<drivers::TofCamera> openCamera(const std::string& spec, const std::string& sim_config,
                                               const std::string& library = "", DeviceLog log = {});
std::string simulatorLibraryPath();
// A real camera's spec (usb, usb:SERIAL, eth:IP); anything else is refused naming every choice, sim and playback included.
drivers::Sr4000Connection parseCameraSpec(const std::string& spec);

// log: the driver's retries and reconnects (default: stderr).
std::unique_ptr<drivers::PoseSource> openPoseSource(const std::string& spec, const std::string& profile,
                                                    DeviceLog log = {});

}  // namespace keyturn::rig
