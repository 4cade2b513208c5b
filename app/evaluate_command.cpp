// keyturn evaluate: the paper's Table 2 for a dataset — accuracy (mean ± spread
// over folds) per feature set, classifier and protocol, the peers on the same
// views and splits, with confusion matrices and per-class PDF plots
// (learning/evaluation_report.h runs and writes it).
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "cross_sensor_evaluate.h"
#include "cached_features.h"
#include "descriptor_options.h"
#include "fusion_options.h"
#include "keyturn/core/descriptor_parameters.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/dataset/view_poses.h"
#include "keyturn/learning/evaluation_parts.h"
#include "keyturn/learning/evaluation_report.h"
#include "keyturn/learning/feature_cache.h"
#include "learning_options.h"
#include "progress.h"
#include "report_files.h"

namespace keyturn::app {
namespace {

const char* kDefaultFeatures =
    "kpd2 kpd3 kpa3 gkpd2 gkpd1 gkpcd2 kpd2+kpa3 kpd2+gkpd2 kpd2+gkpcd2 kpd2+gkpd2+gkpcd2 "
    "kpa3+kpd2+gkpd2+gkpcd2 u_kpd2+u_gkpd2 u_kpa3+u_kpd2+u_gkpd2+u_gkpcd2 esf vfh ourcvfh d2 d3 a3";

struct EvaluateArgs {
  std::string dataset, features = kDefaultFeatures, classifiers = "xgboost,mlp",
                       protocols = "kfold10,leave-elevation,leave-instance", bins, out;
  std::string shard;  // "I/N": train and test this share of the folds into a part
  bool json = false, quiet = false, merge = false;
  int jobs = 0, inner_folds = 3;
  std::uint64_t split_seed = 7;
  std::string label;  // "": each protocol's own
  std::vector<std::string> train_extra;
  std::string other_camera;  // --protocol cross-sensor: the same views through another camera
  DescriptorFlags flags;
  learning::ClassifierParams params;
  learning::OpenSetOptions open_set{learning::openSetMethods()};
  FusionFlags fusion;
};

// --protocol fusion and --protocol nbv are runs of their own (app/fusion_evaluate.cpp,
// app/nbv_evaluate.cpp): sequences of views, not folds of rows.
int runSequences(const EvaluateArgs& a, const std::string& protocol) {
  if (!a.shard.empty() || a.merge || !a.train_extra.empty() || !a.label.empty())
    throw Error("--protocol " + protocol + " takes none of --shard, --merge, --train-extra, --label");
  FusionEvaluateArgs f{a.dataset, a.features, a.classifiers, a.out, a.params, a.flags.options, a.jobs, a.json, a.quiet, a.fusion};
  if (!a.bins.empty()) {
    if (splitList(a.bins).size() != 1) throw Error("--protocol " + protocol + " measures one bin count, not '" + a.bins + "'");
    descriptorParameter("--bins").set(f.options, a.bins);
  }
  return protocol == "nbv" ? runNbvEvaluate(f) : runFusionEvaluate(f);
}

// --protocol cross-sensor is a run of its own too: two datasets, folds over both (app/cross_sensor_evaluate.cpp).
int runCrossSensor(const EvaluateArgs& a) {
  if (!a.shard.empty() || a.merge || !a.train_extra.empty())
    throw Error("--protocol cross-sensor takes none of --shard, --merge, --train-extra (--other-camera names its twin)");
  CrossSensorEvaluateArgs c{a.dataset, a.other_camera, a.features, a.classifiers, a.out, a.params,
                            a.label.empty() ? learning::LabelKind::Instance : learning::parseLabelKind(a.label),
                            a.flags.options, a.jobs, a.json, a.quiet};
  if (!a.bins.empty()) {
    if (splitList(a.bins).size() != 1) throw Error("--protocol cross-sensor measures one bin count, not '" + a.bins + "'");
    descriptorParameter("--bins").set(c.options, a.bins);
  }
  return runCrossSensorEvaluate(c);
}

int runEvaluate(const EvaluateArgs& a) {
  const auto protocols = splitList(a.protocols);
  if (std::find(protocols.begin(), protocols.end(), "cross-sensor") != protocols.end()) {
    if (protocols.size() != 1) throw Error("--protocol cross-sensor is a run of its own: give it alone, not '" + a.protocols + "'");
    return runCrossSensor(a);
  }
  if (!a.other_camera.empty()) throw Error("--other-camera belongs to --protocol cross-sensor");
  for (const std::string sequences : {"fusion", "nbv"})
    if (std::find(protocols.begin(), protocols.end(), sequences) != protocols.end()) {
      if (protocols.size() != 1)
        throw Error("--protocol " + sequences + " is a run of its own: give it alone, not '" + a.protocols + "'");
      return runSequences(a, sequences);
    }
  if (!a.shard.empty() && (a.merge || a.json))
    throw Error(std::string("--shard writes a part of the report; ") + (a.merge ? "--merge" : "--json") +
                " belongs to the run that merges the parts");
  // A bad I/N is said before the dataset is described.
  const auto [shard, shards] = a.shard.empty() ? std::pair<int, int>{0, 1} : parseShard(a.shard);
  learning::EvaluationPlan plan;
  plan.dataset = a.dataset;
  plan.feature_sets = splitList(a.features);
  plan.classifiers = splitList(a.classifiers);
  plan.protocols = splitList(a.protocols);
  for (const auto& b : splitList(a.bins)) {  // each value checked as --bins is
    DescriptorOptions checked;
    try {
      descriptorParameter("bins").set(checked, b);
    } catch (const Error& e) {
      throw Error(std::string("--bins: ") + e.what());
    }
    plan.bins.push_back(checked.histogram.bins);
  }
  if (plan.bins.empty()) plan.bins.push_back(a.flags.options.histogram.bins);
  plan.split_seed = a.split_seed;
  plan.params = a.params;
  plan.jobs = a.jobs;
  plan.low_keypoints = a.flags.options.low_keypoints;
  plan.inner_folds = a.inner_folds;
  if (!a.label.empty()) plan.label = learning::parseLabelKind(a.label);
  plan.train_extra = a.train_extra;
  plan.open_set = a.open_set;
  // Open-set folds are also read as turns of the table: the views' angles from the manifest.
  for (const auto& p : plan.protocols)
    if (p.rfind("open-set", 0) == 0) plan.azimuth_deg = dataset::datasetAzimuths(a.dataset);
  const auto describe = [&a](const std::string& dataset, int bins) {
    DescriptorOptions options = a.flags.options;
    options.histogram.bins = bins;
    return datasetFeatures(dataset, options, a.jobs, a.quiet, splitList(a.features));
  };
  learning::EvaluationRun run = learning::prepareEvaluation(
      plan, [&](int bins) { return describe(a.dataset, bins); }, describe);
  const std::filesystem::path out(a.out);
  if (!a.shard.empty()) {
    Progress progress("evaluate", learning::foldJobs(run, shard, shards).size(), !a.quiet);
    learning::evaluateRows(run, [&] { progress.advance(); }, shard, shards);
    progress.finish();
    const std::string part = learning::evaluationPartPath(a.out, shard, shards);
    writeFileDurably(part, learning::evaluationPartJson(run, shard, shards));
    if (!a.quiet) std::cerr << "keyturn evaluate: part " << a.shard << " in " << formatDuration(run.total_s) << " → " << part << "\n";
    return 0;
  }
  if (a.merge) {
    const int parts = learning::mergeEvaluationParts(run, a.out);
    if (!a.quiet) std::cerr << "keyturn evaluate: merged " << parts << " parts\n";
  } else {
    Progress progress("evaluate", run.totalFolds(), !a.quiet);
    learning::evaluateRows(run, [&] { progress.advance(); });
    progress.finish();
  }

  const learning::EvaluationReport report = learning::evaluationReport(run);
  writeReportFiles(a.out, report);
  if (a.json) std::cout << report.json;
  if (!a.quiet)
    std::cerr << "keyturn evaluate: " << run.rows.size() << " rows in " << formatDuration(run.total_s) << " → "
              << (out / "report.md").string() << "\n";
  return 0;
}

}  // namespace

Command addEvaluateCommand(CLI::App& app) {
  auto a = std::make_shared<EvaluateArgs>();
  auto* cmd = app.add_subcommand("evaluate", "Cross-validated accuracy per feature set, classifier and protocol (Table 2)");
  cmd->add_option("dataset", a->dataset, "Dataset folder (manifest.csv)")->required();
  cmd->add_option("--features", a->features,
                  "Feature sets, comma-separated (or one quoted argument, space-separated); '+' concatenates blocks (kpd2 kpd3 kpa3 gkpd1 gkpd2 "
                  "gkpcd2, u_* on random keypoints, d2 d3 a3, s_* in RMS radii, size, esf vfh ourcvfh, kpset: the keypoints, for setnet); "
                  "'A|B' chooses A or B per fold by nested validation on the training views")
      ->capture_default_str();
  cmd->add_option("--classifier", a->classifiers, "xgboost, mlp, setnet (a set network over the keypoints: features kpset or kpset+…), comma-separated")->capture_default_str();
  cmd->add_option("--protocol", a->protocols,
                  "kfoldN, leave-elevation, leave-instance, open-set[N] (N groups of categories held out as unknowns, "
                  "default 5), open-set-instance[N] (the same, and of every other category with two or more instances "
                  "one instance never trained on: a category model's two kinds of new object), fixed:FILE; or fusion alone (accuracy against the number of views of one object, "
                  "one feature set and classifier, under leave-instance and leave-elevation), or nbv alone (next "
                  "best view against fixed steps, the same way), or cross-sensor alone (with --other-camera: trained on "
                  "either camera's views or both, tested on each, one elevation left out at a time)")
      ->capture_default_str();
  cmd->add_option("--split-seed", a->split_seed, "Seed of the k-fold shuffle")->capture_default_str();
  cmd->add_option("--inner-folds", a->inner_folds,
                  "Inner folds per fold for a choice 'A|B' (the protocol's other folds, spread evenly)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--label", a->label,
                  "instance or category, for every protocol (default: instance, category for leave-instance; "
                  "leave-instance is always category)");
  cmd->add_option("--train-extra", a->train_extra,
                  "Dataset of the same views rendered again (keyturn simulate --jitter): a view's twin is trained on "
                  "only where the view is; repeatable")
      ->allow_extra_args(false)  // one folder per --train-extra: the dataset positional stays free
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--other-camera", a->other_camera,
                  "Protocol cross-sensor: the dataset's views through another camera (keyturn simulate --camera "
                  "openni2 with the same objects, elevations and step)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out,-o", a->out, "Report folder")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views / folds (default: all cores)");
  cmd->add_flag("--json", a->json, "Also print the report as JSON on standard output");
  cmd->add_option("--shard", a->shard,
                  "Train and test only the share I of N of the trainings (I/N, for array jobs) into "
                  "OUT/parts/part-I-of-N.json");
  cmd->add_flag("--merge", a->merge, "Write the report from the parts in OUT/parts/ (run with the parts' options)");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->flags.add(*cmd, false);
  // evaluate's --bins takes a list (the sweep of the paper's Fig. 20).
  cmd->remove_option(cmd->get_option("--bins"));
  cmd->add_option("--bins", a->bins, "Histogram bins; a list sweeps them, e.g. 16,32,64")->default_str("32");
  addClassifierOptions(*cmd, a->params);
  addOpenSetOptions(*cmd, a->open_set);
  a->fusion.addEvaluationOptions(*cmd);
  return {cmd, [a] { return runEvaluate(*a); }};
}

}  // namespace keyturn::app
