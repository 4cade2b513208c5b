// keyturn capture: one turntable sequence at one camera elevation into an
// SR4K-D style dataset. Re-running the same command resumes an interrupted
// capture; Ctrl-C stops cleanly after the current view.
#include <atomic>
#include <csignal>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "device_options.h"
#include "keyturn/core/error.h"
#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/rig/capture.h"
#include "keyturn/rig/capture_rig.h"
#include "keyturn/dataset/sidecars.h"
#include "progress.h"
#include "keyturn/dataset/dataset_layout.h"

namespace keyturn::app {
namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

struct CaptureArgs {
  std::string camera = "sim", pose = "sim", profile = "keyturn-sim";  // read into devices' specs
  rig::CaptureDevices devices;  // the simulated camera's options included
  rig::CaptureOptions o;        // the sequence
  std::string out, calibration;
  bool quiet = false;
};

// The calibration file, the pose source (and its profile) and the camera are opened before the
// dataset's files are written (only its lock is taken first), so a bad one is named before anything
// else is written.
int captureSequence(CaptureArgs a) {
  rig::CaptureOptions& o = a.o;
  if (!a.calibration.empty()) (void)dataset::readAxisCalibration(a.calibration);  // a bad file is named before any device opens
  a.devices.camera = cameraSpec(a.camera, "", "");
  a.devices.pose = poseSpec(a.pose, a.profile);
  rig::refusePlaybackInto(a.devices, a.out);
  // One writer at a time, the lock taken before the simulated rig writes its state into DATASET/.sim.
  dataset::DatasetLock lock(a.out);
  a.devices.sim.dir = dataset::datasetPath(a.out, dataset::kSimulatorFolder);
  a.devices.sim.camera.elevation_deg = o.elevation_deg;
  std::optional<rig::CaptureRig> opened;
  try {
    opened.emplace(a.devices);
  } catch (const rig::SimulatedTurntableNeedsSimulatedCamera&) {
    throw Error("--pose sim needs --camera sim or openni2 (the simulated OpenNI2 camera): the simulated table and "
                "camera share one world");
  }
  rig::CaptureRig& capture_rig = *opened;
  o.camera_from_turntable_zero = capture_rig.cameraFromTurntable();
  dataset::Dataset dataset(a.out, std::move(lock));
  if (const std::size_t n = dataset.temporariesRemoved())
    std::cerr << "keyturn capture: removed " << n << " leftover temporary file" << (n == 1 ? "" : "s")
              << " of an interrupted write\n";
  if (!a.calibration.empty()) {
    // A measured axis overrides even the simulator's exact one; it is kept with the dataset.
    o.camera_from_turntable_zero = dataset::adoptAxisCalibration(a.calibration, a.out);
  }
  if (o.elevation_label.empty()) o.elevation_label = std::to_string(static_cast<int>(std::lround(o.elevation_deg)));
  o.stop = &g_stop;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  const std::size_t total = rig::sequenceAngles(o).size();
  Progress progress("capture " + o.cls + "/" + o.instance + " e" + o.elevation_label, total, !a.quiet);
  const rig::CaptureReport rep = rig::runCapture(capture_rig.camera(), capture_rig.pose(), dataset, o,
                                                 [&](const rig::CaptureProgress&) { progress.advance(); });
  progress.finish();
  std::cerr << "keyturn capture: " << rep.written << " views written, " << rep.skipped << " already there"
            << (rep.redos ? ", " + std::to_string(rep.redos) + " redone (table moved)" : "") << " → " << a.out << "\n";
  if (const auto* table = capture_rig.simulatedTurntable())
    std::cerr << "keyturn capture: simulated turntable: " << table->server().requests() << " requests, "
              << table->server().faultsInjected() << " faults injected\n";
  if (const auto* sr = dynamic_cast<const drivers::Sr4000Camera*>(&capture_rig.camera()))
    std::cerr << "keyturn capture: camera reopened " << sr->reconnects() << " times\n";
  if (rep.stopped) {
    std::cerr << "keyturn capture: stopped; run the same command again to resume\n";
    return 130;
  }
  return 0;
}

// A capture that fails before its first view leaves no dataset behind (verify would call an empty
// one OK); the simulated rig's state folder is made before the devices open, so it goes too.
int runCapture(const CaptureArgs& a) {
  const bool fresh = !std::filesystem::exists(a.out);
  try {
    return captureSequence(a);
  } catch (const Error&) {
    if (fresh) dataset::removeDatasetWithoutViews(a.out);
    throw;
  }
}

int runVerify(const std::string& root) {
  const dataset::VerifyReport r = dataset::Dataset::verify(root);
  std::cout << r.text(root);
  return r.good() ? 0 : 1;
}

}  // namespace

Command addCaptureCommand(CLI::App& app) {
  auto a = std::make_shared<CaptureArgs>();
  auto* cmd = app.add_subcommand("capture", "Capture a turntable sequence into a dataset (resumable)");
  cmd->add_option("--camera", a->camera, "sim, usb, usb:SERIAL, eth:IP, openni2[:URI] (with --pose sim: the simulated OpenNI2 camera), playback:DATASET[@FPS] (a recording) or playback:FILE.oni")->capture_default_str();
  cmd->add_option("--pose", a->pose, "sim (the simulated or played-back rig's own), modbus-tcp:HOST:PORT[@UNIT], modbus-rtu:DEVICE[:BAUD[:8N1]][@UNIT] or can:IFACE")
      ->capture_default_str();
  cmd->add_option("--profile", a->profile, "Modbus register map (JSON file, generic-encoder, keyturn-sim); for can: the CANopen axes file")
      ->capture_default_str();
  cmd->add_option("--class", a->o.cls, "Object class")->required();
  cmd->add_option("--instance", a->o.instance, "Object instance")->required();
  cmd->add_option("--elevation", a->o.elevation_deg, "Camera elevation above the turntable (°)")->capture_default_str();
  cmd->add_option("--elevation-label", a->o.elevation_label, "Label of this elevation (default: the degrees)");
  cmd->add_option("--start", a->o.start_deg, "First angle (°)")->capture_default_str();
  cmd->add_option("--step", a->o.step_deg, "Angle step (°)")->capture_default_str();
  cmd->add_option("--range", a->o.range_deg, "Angles covered (°)")->capture_default_str();
  cmd->add_option("--frames", a->o.frames, "Frames per view (per-pixel median)")->capture_default_str();
  cmd->add_option("--discard", a->o.discard_frames, "Frames discarded after the table settles")->capture_default_str();
  cmd->add_option("--settle", a->o.settle_s, "Time the pose must stay within tolerance (s)")->capture_default_str();
  cmd->add_option("--tolerance", a->o.tolerance_deg, "Pose tolerance (°)")->capture_default_str();
  cmd->add_option("--mesh", a->devices.sim.camera.mesh, "Simulated camera: the object's mesh (PLY/OBJ/STL/OFF), builtin:mug or builtin:sphere-target")
      ->capture_default_str();
  cmd->add_option("--distance", a->devices.sim.camera.distance, "Simulated camera: distance to the object (m); 0 = operator placement");
  cmd->add_option("--seed", a->devices.sim.camera.seed, "Simulated camera: noise seed")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Dataset folder")->required();
  cmd->add_flag("--quiet,-q", a->quiet, "No progress bar");
  cmd->add_option("--sim-faults", a->devices.sim.camera.fault_rate,
                  "Simulated devices: probability of a random fault per camera acquisition and per turntable request")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--world", a->devices.sim.world,
                  "Simulated camera with a separately running `keyturn sim turntable --world FILE`: the shared world file");
  cmd->add_option("--calibration", a->calibration,
                  "Axis calibration from keyturn calibrate-axis: gives every view its camera-from-turntable "
                  "transform (copied into the dataset as " + std::string(dataset::kCalibrationFile) + ")");
  return {cmd, [a] { return runCapture(*a); }};
}

Command addVerifyCommand(CLI::App& app) {
  auto root = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("verify", "Check a dataset: missing, corrupt (SHA-256), orphan and duplicate files");
  cmd->add_option("dataset", *root, "Dataset folder")->required();
  return {cmd, [root] { return runVerify(*root); }};
}

}  // namespace keyturn::app
