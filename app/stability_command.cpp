// keyturn stability: how far each function's PDF moves when a view moves rigidly, is resampled,
// jittered, given the sensor's noise or rounded to a depth image's millimetres — against how far
// apart different views are, with PCL's ESF and VFH on the same clouds. The study is core's
// (stability_study.h); this parses, loads, calls, draws and prints.
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "cached_features.h"
#include "depth_image_options.h"
#include "descriptor_options.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/studies/stability_study.h"
#include "keyturn/core/view_files.h"
#include "keyturn/sim/tof_view.h"
#include "keyturn/plots/report_plots.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct StabilityArgs {
  std::vector<std::string> inputs;
  std::string out, perturbations = "all", pcl_input = "given", group_by = "file", functions = "kpd2,kpd3,kpa3,gkpd1,gkpd2,gkpcd2,d1,d2,d3,d4,a3";
  bool builtin = false, json = false, no_pcl = false, no_scaled = false, quiet = false;
  int draws = 3, jobs = 0;
  unsigned long long seed = 1;
  DescriptorFlags flags;
  DepthImageFlags depth;
};

std::string groupOf(const std::string& file, const std::string& rule) {
  namespace fs = std::filesystem;
  if (rule == "file") return file;
  if (rule == "folder") return fs::path(file).parent_path().string();
  throw Error("--group-by must be file or folder, not '" + rule + "'");
}

std::vector<StabilityView> loadViews(const StabilityArgs& a) {
  std::vector<StabilityView> views;
  if (a.builtin) views.push_back({"builtin:mug", "builtin:mug", sim::builtinBenchmarkView()});
  const DepthImageOptions depth = a.depth.toOptions();
  std::vector<std::string> loose;
  for (const auto& in : a.inputs) {
    if (!isDataset(in)) {
      loose.push_back(in);
      continue;
    }
    for (const auto& v : datasetViews(in))  // a dataset's views, grouped by object (class/instance)
      views.push_back({v.id, v.cls + "/" + v.instance, loadCloud(v.path, v.depth)});
  }
  const ViewFileList list = collectViewFiles(loose, depth.intrinsics.has_value());
  for (const auto& e : list.errors) throw Error(e);
  for (const auto& f : list.files) views.push_back({f, groupOf(f, a.group_by), loadCloud(f, depth)});
  return views;
}

int runStability(const StabilityArgs& a) {
  StabilityOptions o;
  o.descriptor = a.flags.toOptions();
  o.descriptor.features = parseFeatureList(a.functions);
  o.descriptor.scaled_twin = !a.no_scaled;
  o.pcl_descriptors = !a.no_pcl;
  o.pcl_input = pclInputNamed(a.pcl_input);
  o.repetitions = a.draws;
  o.seed = a.seed;
  o.jobs = a.jobs;
  o.perturbations.clear();
  std::stringstream names(a.perturbations);
  for (std::string n; std::getline(names, n, ',');)
    for (const auto& p : perturbationsNamed(n)) o.perturbations.push_back(p);
  const std::vector<StabilityView> views = loadViews(a);
  if (views.size() < 2) throw Error("stability needs at least two views (files, folders, a dataset or --builtin)");

  std::unique_ptr<Progress> bar;
  StabilityProgress progress{
      [&](std::size_t n) { bar = std::make_unique<Progress>("stability", n, !a.quiet); },
      [&] { bar->advance(); }, [&] { bar->finish(); }};
  const StabilityStudy s = runStabilityStudy(views, o, progress);
  for (const auto& e : s.errors) std::cerr << "keyturn stability: " << e << " (left out)\n";

  std::string input;
  for (const auto& in : a.inputs) input += (input.empty() ? "" : " ") + in;
  if (a.builtin) input += input.empty() ? "builtin:mug" : " builtin:mug";
  const std::string md = stabilityMarkdown(s, input), json = stabilityJson(s, input);
  if (!a.out.empty()) {
    std::filesystem::create_directories(a.out);
    writeFileDurably(a.out + "/stability.md", md);
    writeFileDurably(a.out + "/stability.json", json);
    plots::saveReportPlots(stabilityPlots(s), a.out);
  }
  std::cout << (a.json ? json + "\n" : md + (a.out.empty() ? "" : "Report: " + a.out + "\n"));
  return 0;
}

}  // namespace

Command addStabilityCommand(CLI::App& app) {
  auto a = std::make_shared<StabilityArgs>();
  auto* cmd = app.add_subcommand(
      "stability", "How far each function's PDF moves under rigid motion, resampling and noise, against the distance between views");
  cmd->add_option("inputs", a->inputs, "View files, folders of them, or keyturn datasets");
  cmd->add_flag("--builtin", a->builtin, "Add the built-in simulated SR4000 view (a mug)");
  cmd->add_option("--perturbations", a->perturbations,
                  "Comma list of perturbation names, 'rigid' or 'all' (docs/descriptors.md, section Stability)")
      ->capture_default_str();
  cmd->add_option("--functions", a->functions, "Functions to study")->capture_default_str();
  cmd->add_option("--draws", a->draws, "Draws of each perturbation per view")->capture_default_str()->check(CLI::Range(1, 1000));
  cmd->add_option("--perturbation-seed", a->seed, "Seed of the perturbations")->capture_default_str();
  cmd->add_option("--group-by", a->group_by,
                  "Loose files: which views show one object (file: each file its own; folder) — between-view "
                  "distances pair different groups")
      ->capture_default_str();
  cmd->add_flag("--no-pcl", a->no_pcl, "Leave out PCL's ESF and VFH");
  cmd->add_option("--pcl-input", a->pcl_input,
                  "What PCL's ESF and VFH describe: given (each view's cloud as it is, as a PCL user computes them) "
                  "or filtered (the view after keyturn's filter)")
      ->capture_default_str()
      ->check(CLI::IsMember({"given", "filtered"}));
  cmd->add_flag("--no-scaled", a->no_scaled, "Leave out the scaled twins (s_kpd2, …)");
  cmd->add_option("--jobs,-j", a->jobs, "Views studied in parallel (0: one per core)");
  cmd->add_option("--out,-o", a->out, "Report folder (Markdown, JSON, PNG plots)");
  cmd->add_flag("--json", a->json, "Print the summary as JSON");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->flags.add(*cmd, false);
  a->depth.add(*cmd);
  return {cmd, [a] { return runStability(*a); }};
}

}  // namespace keyturn::app
