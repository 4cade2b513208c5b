#pragma once
// The one place keyturn opens devices: a CameraSpec or a PoseSpec (device_spec.h) becomes a
// TofCamera or a PoseSource, for the CLI, capture and the studio alike.
//   simulated  libmesasr-sim (PREFIX/lib/keyturn/mesasr-sim, or $KEYTURN_MESASR_SIM) through the real SR4000 driver,
//              its configuration file passed explicitly (KTSIM_OpenWithConfig, drivers/mesasr_api.h)
//   usb, eth   MESA's libMesaSR (the spec's library, else $KEYTURN_MESASR_LIB or the usual sonames)
//   playback   a dataset replayed (dataset_playback.h); its camera and pose source share one timeline
//   openni2    a depth camera through OpenNI2 (drivers/openni2_camera.h); playback:FILE.oni: OpenNI2's
//              recording through its libOniFile driver
//   pose sim   the simulated turntable (simulated_rig.h) writing the world the simulated camera follows
//   modbus-*   a Modbus turntable or encoder with its register profile; can: CANopen axes
// A new kind of device is one case in openCamera/openPoseSource here.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/rig/device_spec.h"
#include "keyturn/sim/turntable_sim.h"

namespace keyturn::rig {

class Recording;
class SimulatedTurntable;

// The driver's retries and reconnects (default: stderr, "keyturn: camera: …" / "keyturn: turntable: …").
using DeviceLog = std::function<void(const std::string&)>;

// libmesasr-sim's libmesasr.so: $KEYTURN_MESASR_SIM, else PREFIX/lib/keyturn/mesasr-sim/ (install_layout.h).
std::string simulatorLibraryPath();

class DeviceFactory {
 public:
  // simulated_turntable: the server a pose "sim" starts (its world_file is the world the simulated
  // camera's configuration names; without one, pose sim is refused).
  explicit DeviceFactory(sim::TurntableServerOptions simulated_turntable = {});
  ~DeviceFactory();

  // Both throw keyturn::Error in one line naming the device and what went wrong.
  std::unique_ptr<drivers::TofCamera> openCamera(const CameraSpec& spec, DeviceLog log = {});
  std::unique_ptr<drivers::PoseSource> openPoseSource(const PoseSpec& spec, DeviceLog log = {});
  std::unique_ptr<SimulatedTurntable> openSimulatedTurntable(DeviceLog log = {});

  // Camera ← turntable at 0° of the camera opened last: exact for a simulated one (from its
  // configuration), the recorded calibration for a playback, none for a real camera.
  std::optional<Eigen::Matrix4d> cameraFromTurntable() const;

 private:
  // A camera and a pose source of the same recording share its timeline, whichever opens first.
  std::shared_ptr<Recording> recording(const PlaybackSpec& spec);

  sim::TurntableServerOptions simulated_turntable_;
  mutable std::mutex mutex_;  // the studio opens its camera and its pose source on two threads
  std::optional<Eigen::Matrix4d> camera_from_turntable_;
  PlaybackSpec playing_;
  std::shared_ptr<Recording> recording_;
};

}  // namespace keyturn::rig
