// keyturn consistency: how much one object's description changes as it turns
// (the paper's Figs 15–16) — the dissimilarity of the view at each rotation to
// the first view, keypoint functions against Osada's shape functions
// (learning/consistency.h).
#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "cached_features.h"
#include "descriptor_options.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/learning/consistency.h"
#include "keyturn/plots/report_plots.h"

namespace keyturn::app {
namespace {

struct ConsistencyArgs {
  std::string dataset, object, elevation, out, measure = "bhattacharyya";
  std::string functions = "kpd2,kpd3,kpa3,gkpd2,d2,d3,a3";
  int jobs = 0;
  bool quiet = false;
  DescriptorFlags flags;
};

int runConsistency(const ConsistencyArgs& a) {
  (void)learning::objectParts(a.object);  // a bad name is said before the dataset is described
  const learning::FeatureTable t = datasetFeatures(a.dataset, a.flags.options, a.jobs, a.quiet);
  learning::ConsistencyQuery q{a.object, a.elevation, {}, parseDissimilarity(a.measure), a.measure};
  std::stringstream ss(a.functions);
  for (std::string f; std::getline(ss, f, ',');) q.blocks.push_back(f);
  const learning::ConsistencyReport report = learning::consistency(t, q, a.dataset);
  std::filesystem::create_directories(a.out);
  plots::saveReportPlots(report.plots, a.out);
  const std::string csv_path = (std::filesystem::path(a.out) / "consistency.csv").string();
  writeFileDurably(csv_path, report.csv);
  if (!a.quiet) std::cerr << "keyturn consistency: " << a.object << " → " << csv_path << " and consistency_e*.png\n";
  return 0;
}

}  // namespace

Command addConsistencyCommand(CLI::App& app) {
  auto a = std::make_shared<ConsistencyArgs>();
  auto* cmd = app.add_subcommand("consistency", "Dissimilarity of each rotation of an object to its first view (Figs 15-16)");
  cmd->add_option("dataset", a->dataset, "Dataset folder")->required();
  cmd->add_option("--object", a->object, "CLASS/INSTANCE")->required();
  cmd->add_option("--elevation", a->elevation, "Only this elevation label (default: each)");
  cmd->add_option("--functions", a->functions, "Feature blocks to compare")->capture_default_str();
  cmd->add_option("--measure", a->measure, "bhattacharyya, chi2, l1, js or emd")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Output folder (CSV and PNG)")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views when describing");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->flags.add(*cmd, false);
  return {cmd, [a] { return runConsistency(*a); }};
}

}  // namespace keyturn::app
