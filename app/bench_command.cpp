// keyturn bench: per-stage time of the descriptor chain (median, min, max over
// repetitions, one thread) with the keypoint count beside it, and PCL's
// ISSKeypoint3D, ESF and VFH timed on the same filtered cloud in the same run.
// A view that cannot be read or described is named on stderr (and as an "error"
// entry in --json); the others are still timed, and the exit status is then 1.
// --scaling times the chain against input size instead (keyturn/bench/scaling.h); --startup
// times the tool's own start-up (keyturn/bench/startup_timing.h).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "depth_image_options.h"
#include "descriptor_options.h"
#include "keyturn/bench/scaling.h"
#include "keyturn/bench/startup_timing.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/install_layout.h"
#include "keyturn/sim/tof_view.h"
#include "keyturn/plots/report_plots.h"
#include "progress.h"
#include "keyturn/core/view_files.h"


namespace keyturn::app {
namespace {

using bench::BenchRuns;

struct BenchArgs {
  std::vector<std::string> files;
  BenchRuns runs;
  bool json = false;
  bool no_builtin = false;
  bool scaling = false;
  bool startup = false;
  std::vector<std::size_t> sizes = bench::defaultScalingSizes();
  std::string plot;
  DescriptorFlags flags;
  DepthImageFlags depth;
};

// A progress line per timed view.
bench::RunProgress progressLines() {
  auto bar = std::make_shared<std::unique_ptr<Progress>>();
  return [bar](const std::string& label, int done, int total) {
    if (done == 0) *bar = std::make_unique<Progress>(label, static_cast<std::size_t>(total), true);
    else (*bar)->advance();
    if (done == total) (*bar)->finish();
  };
}

int runBench(BenchArgs a) {
  a.runs.progress = progressLines();
  std::vector<bench::ViewToTime> views;
  if (!a.no_builtin) views.push_back({"builtin:mug", sim::builtinBenchmarkView, ""});
  const DepthImageOptions depth = a.depth.toOptions();
  const ViewFileList list = collectViewFiles(a.files, depth.intrinsics.has_value());
  for (const auto& e : list.errors)  // "ARGUMENT: what is wrong"
    for (const auto& in : a.files)
      if (e.rfind(in + ": ", 0) == 0) views.push_back({in, nullptr, e.substr(in.size() + 2)});
  for (const auto& f : list.files) views.push_back({f, [f, depth] { return loadCloud(f, depth); }, ""});
  if (views.empty()) throw Error("nothing to benchmark (--no-builtin and no files)");
  const nlohmann::json out = bench::benchViews(views, a.runs, a.flags.toOptions(),
                                               [](const std::string& name, const std::string& error) {
                                                 std::cerr << "keyturn bench: " << name << ": " << error << "\n";
                                               });
  if (a.json) std::cout << out.dump(2) << "\n";
  else
    for (const auto& v : out["views"])
      if (!v.contains("error")) std::fputs(bench::viewTable(v).c_str(), stdout);
  const int failed = out["failed"].get<int>();
  if (failed)
    std::cerr << "keyturn bench: " << failed << " of " << views.size() << " views could not be timed\n";
  return failed ? 1 : 0;
}

int runScalingCommand(const BenchArgs& a) {
  if (a.files.size() > 1) throw Error("bench --scaling takes one frame (or none: the shipped Kinect frame)");
  bench::ScalingArgs s;
  s.file = a.files.empty() ? (dataDirectory() / "frames/mosd_learn0.pcd").string() : a.files[0];
  s.depth = a.depth.toOptions();
  s.sizes = a.sizes;
  s.runs = a.runs;
  if (!a.json) s.runs.progress = progressLines();
  s.warn = [](const std::string& line) { std::cerr << "keyturn bench --scaling: " << line << "\n"; };
  const nlohmann::json out = bench::runScaling(s, a.flags.toOptions());
  if (a.json) std::cout << out.dump(2) << "\n";
  else std::fputs(("keyturn bench --scaling " + bench::scalingTable(out)).c_str(), stdout);
  if (!a.plot.empty()) {
    plots::saveReportPlots({{bench::scalingPlot(out, a.plot)}, {}}, "");
    if (!a.json) std::printf("\nplot: %s\n", a.plot.c_str());
  }
  return out["failed"].get<int>() ? 1 : 0;
}

// `keyturn --help` and a one-view describe, each as a whole process: what a user waits for
// before a one-off command prints anything.
int runStartupCommand(const BenchArgs& a) {
  namespace fs = std::filesystem;
  if (a.files.size() > 1) throw Error("bench --startup takes one view (or none: the built-in SR4000 view)");
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("bench --startup: cannot find this program (/proc/self/exe: " + ec.message() + ")");
  const fs::path scratch = fs::temp_directory_path() / ("keyturn-startup-" + std::to_string(getpid()));
  std::string view = a.files.empty() ? "" : a.files[0];
  if (view.empty()) {
    fs::create_directories(scratch);
    view = (scratch / "sr4000_view.pcd").string();
    saveCloud(view, sim::builtinBenchmarkView());
  }
  std::vector<bench::ProcessTiming> timings;
  try {
    const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
        {"keyturn --help", {self.string(), "--help"}},
        {"keyturn describe " + std::string(a.files.empty() ? "<SR4000 view>" : "VIEW"), {self.string(), "describe", view}}};
    std::unique_ptr<Progress> bar;
    if (!a.json) bar = std::make_unique<Progress>("bench --startup", commands.size(), true);
    for (const auto& [label, argv] : commands) {
      timings.push_back(bench::timeProcess(label, argv, a.runs.repetitions));
      if (bar) bar->advance();
    }
    if (bar) bar->finish();
  } catch (...) {
    fs::remove_all(scratch, ec);
    throw;
  }
  fs::remove_all(scratch, ec);
  int failed = 0;
  nlohmann::json out = {{"timings", nlohmann::json::array()}};
  for (const auto& t : timings) {
    out["timings"].push_back(bench::timingJson(t));
    for (int code : t.exit_codes)
      if (code != 0) {
        std::cerr << "keyturn bench --startup: '" << t.label << "' exited with " << code << "\n";
        ++failed;
        break;
      }
  }
  if (a.json) std::cout << out.dump(2) << "\n";
  else std::fputs(bench::startupTable(timings).c_str(), stdout);
  return failed ? 1 : 0;
}

}  // namespace

Command addBenchCommand(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd = app.add_subcommand("bench", "Time every stage of the chain against PCL's ISS, ESF and VFH");
  cmd->add_option("files", args->files,
                  "Extra PCD/PLY views, depth PNGs or folders of them to time (the built-in view always runs first); "
                  "with --scaling, the one frame to scale");
  auto* reps = cmd->add_option("--repetitions,-n", args->runs.repetitions, "Runs per view (--scaling: 5 unless given)")
      ->capture_default_str()->check(CLI::Range(1, 100000));
  auto* pcl_reps = cmd->add_option("--pcl-repetitions", args->runs.pcl_repetitions,
                                   "Runs of each PCL baseline (--scaling: 3 unless given)")
      ->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_flag("--json", args->json, "Print one JSON object (milliseconds) instead of a table");
  cmd->add_flag("--no-builtin", args->no_builtin, "Skip the built-in synthetic SR4000 view");
  auto* scaling = cmd->add_flag("--scaling", args->scaling,
                                "Time the whole chain against input size on one real frame (default: the shipped "
                                "640 × 480 Kinect frame data/frames/mosd_learn0.pcd); see docs/benchmarks.md");
  cmd->add_option("--sizes", args->sizes, "Input sizes for --scaling, comma-separated")
      ->delimiter(',')->needs(scaling)->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
  cmd->add_option("--plot", args->plot, "With --scaling: also write a log-log PNG of time against size")
      ->needs(scaling);
  cmd->add_flag("--startup", args->startup,
                "Time this tool's start-up as whole processes: `keyturn --help` and a one-view describe (of the "
                "built-in SR4000 view, or the one view given), wall time and peak memory; -n runs each (10 unless "
                "given)")
      ->excludes(scaling);
  args->flags.add(*cmd);
  args->depth.add(*cmd);
  return {cmd, [args, reps, pcl_reps] {
            if (args->startup) {
              if (reps->count() == 0) args->runs.repetitions = 10;
              return runStartupCommand(*args);
            }
            if (!args->scaling) return runBench(*args);
            if (reps->count() == 0) args->runs.repetitions = 5;
            if (pcl_reps->count() == 0) args->runs.pcl_repetitions = 3;
            return runScalingCommand(*args);
          }};
}

}  // namespace keyturn::app
