#pragma once
// An SR4K-D style dataset generated on the simulated rig (keyturn simulate): the
// real capture path (drivers, Modbus, libmesasr-sim) for every object of a list
// at every elevation, with simulated motion and settling shrunk far below real
// time. Resumable like a capture: views already in the dataset are skipped.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/rig/capture.h"
#include "keyturn/dataset/object_list.h"

namespace keyturn::rig {

// The simulated camera that renders a dataset's views: the SR4000 (libmesasr-sim through libMesaSR's
// interface, 176 × 144 time of flight) or the Kinect-class camera (the simulated OpenNI2 driver through
// Debian's libOpenNI2, 640 × 480 structured light). The same view ids either way, so a dataset of one
// is the other's twin (evaluate --train-extra, --protocol cross-sensor; train --train-extra).
enum class SimulatedCamera { Sr4000, OpenNi2 };
// "sr4000" or "openni2"; throws keyturn::Error naming the choices for another name.
SimulatedCamera parseSimulatedCamera(const std::string& name);
// A comma-separated list of them ("sr4000,openni2").
std::vector<SimulatedCamera> parseSimulatedCameras(const std::string& list);
const char* simulatedCameraName(SimulatedCamera camera);

// Per-view jitter, for a training-side twin of a dataset (evaluate --train-extra): every view
// rendered with its own framing distance, elevation, camera roll and integration time, drawn
// from (seed, class, instance, elevation, angle) alone, so a resumed or repeated run draws the same.
struct ViewJitter {
  double distance = 0;       // framing distance × (1 ± distance), uniform
  double elevation_deg = 0;  // nominal elevation ± this, uniform (the view keeps the nominal label)
  double tilt_deg = 0;       // camera roll about the optical axis ± this, uniform
  double scale = 0;          // object grown × (1 ± scale), uniform; framed for its new size
  int integration_min = 0, integration_max = 0;  // SR4000 integration code, uniform; 0: the camera's own
  bool any() const { return distance > 0 || elevation_deg > 0 || tilt_deg > 0 || scale > 0 || integration_max > 0; }
  // Throws keyturn::Error for a magnitude out of its range (fractions < 0.5, angles ≤ 20°, codes 1–255).
  void check() const;
  // … and for a jitter the camera cannot take (integration time is the SR4000's alone).
  void check(SimulatedCamera camera) const;
};

// One view's draw: what the simulated camera is given for it.
struct JitteredView {
  double distance_scale = 1, elevation_deg = 0, roll_deg = 0, scale = 1;
  int integration = 0;  // 0: left as the camera has it
};
JitteredView drawJitter(const ViewJitter& jitter, std::uint64_t seed, const dataset::ViewKey& view, double elevation_deg);

struct DatasetSimulation {
  std::string out;                  // the dataset folder (its rig's files in OUT/.sim)
  SimulatedCamera camera = SimulatedCamera::Sr4000;
  std::vector<dataset::ObjectRow> objects;
  std::vector<double> elevations;   // degrees; labelled by their whole degrees
  double step_deg = 5;
  std::uint64_t seed = 1;           // sensor noise (and, with jitter, each view's draw)
  ViewJitter jitter;                // none by default: the rig opened once per object and elevation
  std::atomic<bool>* stop = nullptr;  // set (e.g. by Ctrl-C) to stop after the current view

  // Throws keyturn::Error naming list_path and the object whose mesh is missing.
  void checkMeshes(const std::string& list_path) const;
  std::size_t views() const;        // in all, objects × elevations × angles
};

// Writes (or resumes) the dataset; view_done after every view written or skipped.
CaptureReport simulateDataset(const DatasetSimulation& simulation, const std::function<void()>& view_done = {});

}  // namespace keyturn::rig
