// keyturn simulate: the SR4K-D style dataset generator. Runs the real capture
// path (drivers, Modbus, libmesasr-sim) on the simulated rig for every object of
// a CSV list at every elevation. Simulated motion and settling shrink far below
// real time; resumable like capture.
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "keyturn/core/error.h"
#include "keyturn/rig/capture.h"
#include "keyturn/rig/object_list.h"
#include "keyturn/rig/simulated_rig.h"
#include "progress.h"

namespace fs = std::filesystem;

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

std::vector<double> parseList(const std::string& text, const char* what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string tok;
  while (std::getline(ss, tok, ',')) {
    try {
      out.push_back(std::stod(tok));
    } catch (const std::exception&) {
      throw Error(std::string(what) + ": '" + tok + "' is not a number");
    }
  }
  if (out.empty()) throw Error(std::string(what) + ": empty");
  return out;
}

int runSimulate(const SimulateArgs& a) {
  const auto objects = rig::readObjectList(a.objects);
  const auto elevations = parseList(a.elevations, "--elevations");
  for (const auto& o : objects)
    if (!fs::exists(o.mesh)) throw Error(a.objects + ": " + o.cls + "/" + o.instance + ": no mesh at " + o.mesh);
  rig::Dataset dataset(a.out);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  rig::CaptureOptions base;
  base.step_deg = a.step;
  base.settle_s = 0.0;       // the simulated table reports only where it is
  base.discard_frames = 0;   // and the simulated sensor needs no warm-up frames
  base.stop = &g_stop;
  const std::size_t per = rig::sequenceAngles(base).size();
  const std::size_t total = per * objects.size() * elevations.size();
  Progress progress("simulate", total, !a.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t written = 0, skipped = 0;
  for (const auto& obj : objects) {
    for (double el : elevations) {
      if (g_stop) break;
      rig::SimulatedRigOptions so;
      so.dir = a.out + "/.sim";
      so.camera.mesh = obj.mesh;
      so.camera.elevation_deg = el;
      so.camera.seed = a.seed;
      so.fast = true;
      rig::SimulatedRig simrig = rig::openSimulatedRig(so);
      rig::CaptureOptions o = base;
      o.cls = obj.cls;
      o.instance = obj.instance;
      o.elevation_deg = el;
      o.elevation_label = std::to_string(static_cast<int>(std::lround(el)));
      o.camera_from_turntable_zero = simrig.camera_from_turntable;
      const auto rep = rig::runCapture(*simrig.camera, *simrig.turntable, dataset, o,
                                       [&](const rig::CaptureProgress&) { progress.advance(); });
      written += rep.written;
      skipped += rep.skipped;
    }
  }
  progress.finish();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cerr << "keyturn simulate: " << written << " views written, " << skipped << " already there, in "
            << formatDuration(s) << " (" << (s > 0 ? written / s : 0.0) << " views/s) → " << a.out << "\n";
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
