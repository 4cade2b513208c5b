// keyturn capture: one turntable sequence at one camera elevation into an
// SR4K-D style dataset. Re-running the same command resumes an interrupted
// capture; Ctrl-C stops cleanly after the current view.
#include <atomic>
#include <csignal>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "keyturn/core/error.h"
#include "keyturn/drivers/sr4000_camera.h"
#include "keyturn/rig/capture.h"
#include "keyturn/rig/capture_rig.h"
#include "keyturn/rig/sidecars.h"
#include "progress.h"

namespace keyturn::app {
namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

struct CaptureArgs {
  std::string camera = "sim", pose = "sim", profile = "keyturn-sim";
  std::string cls, instance, out;
  double elevation = 30, start = 0, step = 5, range = 360;
  std::string elevation_label;
  int frames = 1, discard = 1;
  double settle = 0.2, tolerance = 0.1;
  std::string mesh = "builtin:mug";
  double distance = 0;
  unsigned long long seed = 1;
  bool quiet = false;
  std::string calibration;
  std::string world;
  double sim_faults = 0;
};

// The calibration file, the pose source (and its profile) and the camera are opened before the
// dataset is created, so a bad one is named before anything is written.
int captureSequence(const CaptureArgs& a) {
  rig::CaptureOptions o;
  if (!a.calibration.empty()) (void)rig::readAxisCalibration(a.calibration);  // a bad file is named before any device opens
  rig::CaptureDevices devices;
  devices.camera = a.camera;
  devices.pose = a.pose;
  devices.profile = a.profile;
  devices.sim.dir = a.out + "/.sim";
  devices.sim.camera.mesh = a.mesh;
  devices.sim.camera.elevation_deg = a.elevation;
  devices.sim.camera.distance = a.distance;
  devices.sim.camera.seed = a.seed;
  devices.sim.camera.fault_rate = a.sim_faults;
  devices.sim.world = a.world;
  rig::CaptureRig capture_rig(devices);
  o.camera_from_turntable_zero = capture_rig.cameraFromTurntable();
  rig::Dataset dataset(a.out);
  if (!a.calibration.empty()) {
    // A measured axis overrides even the simulator's exact one; it is kept with the dataset.
    o.camera_from_turntable_zero = rig::adoptAxisCalibration(a.calibration, a.out);
  }

  o.cls = a.cls;
  o.instance = a.instance;
  o.elevation_deg = a.elevation;
  o.elevation_label = a.elevation_label.empty() ? std::to_string(static_cast<int>(std::lround(a.elevation)))
                                                : a.elevation_label;
  o.start_deg = a.start;
  o.step_deg = a.step;
  o.range_deg = a.range;
  o.frames = a.frames;
  o.discard_frames = a.discard;
  o.settle_s = a.settle;
  o.tolerance_deg = a.tolerance;
  o.stop = &g_stop;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  const std::size_t total = rig::sequenceAngles(o).size();
  Progress progress("capture " + a.cls + "/" + a.instance + " e" + o.elevation_label, total, !a.quiet);
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
    if (fresh) rig::removeDatasetWithoutViews(a.out);
    throw;
  }
}

int runVerify(const std::string& root) {
  const rig::VerifyReport r = rig::Dataset::verify(root);
  auto list = [](const char* what, const std::vector<std::string>& v) {
    for (const auto& f : v) std::cout << what << ": " << f << "\n";
  };
  list("missing", r.missing);
  list("corrupt", r.corrupt);
  list("orphan", r.orphans);
  list("duplicate", r.duplicates);
  list("bad manifest row", r.bad_rows);
  // A dataset without views is not a good one (a capture that never took its first view).
  const bool ok = r.ok() && r.views > 0;
  std::cout << root << ": " << r.views << " views, " << r.missing.size() << " missing, " << r.corrupt.size()
            << " corrupt, " << r.orphans.size() << " orphan, " << r.duplicates.size() << " duplicate files"
            << (ok ? " — OK" : r.ok() ? " — EMPTY (no views)" : " — PROBLEMS") << "\n";
  return ok ? 0 : 1;
}

}  // namespace

Command addCaptureCommand(CLI::App& app) {
  auto a = std::make_shared<CaptureArgs>();
  auto* cmd = app.add_subcommand("capture", "Capture a turntable sequence into a dataset (resumable)");
  cmd->add_option("--camera", a->camera, "sim, usb, usb:SERIAL or eth:IP")->capture_default_str();
  cmd->add_option("--pose", a->pose, "sim, modbus-tcp:HOST:PORT[@UNIT], modbus-rtu:DEVICE[:BAUD[:8N1]][@UNIT] or can:IFACE")
      ->capture_default_str();
  cmd->add_option("--profile", a->profile, "Modbus register map (JSON file, generic-encoder, keyturn-sim); for can: the CANopen axes file")
      ->capture_default_str();
  cmd->add_option("--class", a->cls, "Object class")->required();
  cmd->add_option("--instance", a->instance, "Object instance")->required();
  cmd->add_option("--elevation", a->elevation, "Camera elevation above the turntable (°)")->capture_default_str();
  cmd->add_option("--elevation-label", a->elevation_label, "Label of this elevation (default: the degrees)");
  cmd->add_option("--start", a->start, "First angle (°)")->capture_default_str();
  cmd->add_option("--step", a->step, "Angle step (°)")->capture_default_str();
  cmd->add_option("--range", a->range, "Angles covered (°)")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Frames per view (per-pixel median)")->capture_default_str();
  cmd->add_option("--discard", a->discard, "Frames discarded after the table settles")->capture_default_str();
  cmd->add_option("--settle", a->settle, "Time the pose must stay within tolerance (s)")->capture_default_str();
  cmd->add_option("--tolerance", a->tolerance, "Pose tolerance (°)")->capture_default_str();
  cmd->add_option("--mesh", a->mesh, "Simulated camera: the object's mesh (PLY/OBJ/STL/OFF), builtin:mug or builtin:sphere-target")
      ->capture_default_str();
  cmd->add_option("--distance", a->distance, "Simulated camera: distance to the object (m); 0 = operator placement");
  cmd->add_option("--seed", a->seed, "Simulated camera: noise seed")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Dataset folder")->required();
  cmd->add_flag("--quiet,-q", a->quiet, "No progress bar");
  cmd->add_option("--sim-faults", a->sim_faults,
                  "Simulated devices: probability of a random fault per camera acquisition and per turntable request")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--world", a->world,
                  "Simulated camera with a separately running `keyturn sim turntable --world FILE`: the shared world file");
  cmd->add_option("--calibration", a->calibration,
                  "Axis calibration from keyturn calibrate-axis: gives every view its camera-from-turntable "
                  "transform (copied into the dataset as calibration.json)");
  return {cmd, [a] { return runCapture(*a); }};
}

Command addVerifyCommand(CLI::App& app) {
  auto root = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("verify", "Check a dataset: missing, corrupt (SHA-256), orphan and duplicate files");
  cmd->add_option("dataset", *root, "Dataset folder")->required();
  return {cmd, [root] { return runVerify(*root); }};
}

}  // namespace keyturn::app
