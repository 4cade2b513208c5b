// keyturn simulate: the SR4K-D style dataset generator (rig/dataset_simulation.h);
// resumable like capture.
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>

#include "commands.h"
#include "keyturn/core/string_format.h"
#include "keyturn/rig/dataset_simulation.h"
#include "progress.h"

namespace keyturn::app {
namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

struct SimulateArgs {
  std::string objects, out, elevations = "30,45,60";
  double step = 5;
  unsigned long long seed = 1;
  bool quiet = false;
};

int runSimulate(const SimulateArgs& a) {
  rig::DatasetSimulation sim;
  sim.out = a.out;
  sim.objects = rig::readObjectList(a.objects);
  sim.elevations = parseNumberList(a.elevations, "--elevations");
  sim.step_deg = a.step;
  sim.seed = a.seed;
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
  cmd->add_option("--elevations", a->elevations, "Camera elevations (°), comma-separated")->capture_default_str();
  cmd->add_option("--step", a->step, "Turntable step (°)")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Sensor noise seed")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Dataset folder")->required();
  cmd->add_flag("--quiet,-q", a->quiet, "No progress bar");
  return {cmd, [a] { return runSimulate(*a); }};
}

}  // namespace keyturn::app
