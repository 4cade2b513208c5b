// keyturn simulate: the SR4K-D style dataset generator (rig/dataset_simulation.h);
// resumable like capture.
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <stdexcept>

#include "commands.h"
#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"
#include "keyturn/rig/dataset_simulation.h"
#include "progress.h"

namespace keyturn::app {
namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

struct SimulateArgs {
  std::string objects, out, elevations = "30,45,60", camera = "sr4000";
  double step = 5;
  unsigned long long seed = 1;
  bool quiet = false;
  rig::ViewJitter jitter;
  std::string integration;  // "MIN:MAX" codes
};

// "20:60" → the jitter's integration codes; throws naming --jitter-integration.
void parseIntegrationRange(const std::string& text, rig::ViewJitter& j) {
  if (text.empty()) return;
  const auto colon = text.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument(text);
    std::size_t used = 0;
    j.integration_min = std::stoi(text.substr(0, colon), &used);
    if (used != colon) throw std::invalid_argument(text);
    const std::string hi = text.substr(colon + 1);
    j.integration_max = std::stoi(hi, &used);
    if (used != hi.size()) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw Error("--jitter-integration " + text + ": expected MIN:MAX, SR4000 codes (0.3 ms + code × 0.1 ms)");
  }
}

int runSimulate(const SimulateArgs& a) {
  rig::DatasetSimulation sim;
  sim.out = a.out;
  sim.camera = rig::parseSimulatedCamera(a.camera);
  sim.objects = dataset::readObjectList(a.objects);
  sim.elevations = parseNumberList(a.elevations, "--elevations");
  sim.step_deg = a.step;
  sim.seed = a.seed;
  sim.jitter = a.jitter;
  parseIntegrationRange(a.integration, sim.jitter);
  sim.jitter.check(sim.camera);
  sim.stop = &g_stop;
  sim.checkMeshes(a.objects);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  Progress progress("simulate", sim.views(), !a.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  const rig::CaptureReport rep = rig::simulateDataset(sim, [&] { progress.advance(); });
  progress.finish();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cerr << "keyturn simulate: " << rep.written << " views written, " << rep.skipped << " already there, in "
            << formatDuration(s) << " (" << (s > 0 ? rep.written / s : 0.0) << " views/s) → " << a.out << "\n";
  if (g_stop) {
    std::cerr << "keyturn simulate: stopped; run the same command again to resume\n";
    return 130;
  }
  return 0;
}

}  // namespace

Command addSimulateCommand(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  auto* cmd = app.add_subcommand("simulate", "Generate an SR4K-D style dataset on the simulated rig");
  cmd->add_option("--objects", a->objects, "CSV with class,instance,mesh columns (mesh paths relative to it)")
      ->required();
  cmd->add_option("--camera", a->camera,
                  "sr4000 (libmesasr-sim, 176 × 144 time of flight) or openni2 (the simulated Kinect-class camera "
                  "through OpenNI2, 640 × 480 structured light): the same view ids either way, one dataset per camera")
      ->capture_default_str();
  cmd->add_option("--elevations", a->elevations, "Camera elevations (°), comma-separated")->capture_default_str();
  cmd->add_option("--step", a->step, "Turntable step (°)")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Sensor noise seed")->capture_default_str();
  cmd->add_option("--jitter-distance", a->jitter.distance,
                  "Per view: framing distance × (1 ± F), uniform (a training-side twin, evaluate --train-extra)");
  cmd->add_option("--jitter-elevation", a->jitter.elevation_deg, "Per view: elevation ± DEG, uniform (label kept)");
  cmd->add_option("--jitter-tilt", a->jitter.tilt_deg, "Per view: camera roll about its optical axis ± DEG, uniform");
  cmd->add_option("--jitter-scale", a->jitter.scale,
                  "Per view: the object grown × (1 ± F), uniform, and framed for that size (another instance's size)");
  cmd->add_option("--jitter-integration", a->integration,
                  "Per view: SR4000 integration code uniform in MIN:MAX (30 = 3.3 ms; noise ∝ 1/√time)");
  cmd->add_option("--out,-o", a->out, "Dataset folder")->required();
  cmd->add_flag("--quiet,-q", a->quiet, "No progress bar");
  return {cmd, [a] { return runSimulate(*a); }};
}

}  // namespace keyturn::app
