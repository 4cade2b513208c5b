// keyturn evaluate --protocol fusion: accuracy against the number of views of one object, per
// fusion method and schedule, with the shuffled-poses control, under leave-instance and
// leave-elevation where the dataset has them (learning/fusion_evaluation.h runs and reports it).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>

#include "dataset_features.h"
#include "fusion_options.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/dataset/view_poses.h"
#include "report_files.h"

namespace keyturn::app {

learning::FusionEvaluationOptions FusionFlags::evaluationOptions() const {
  learning::FusionEvaluationOptions o;
  o.fusion = fusion;
  o.max_views = views;
  std::string item;
  std::stringstream in(schedules);
  while (std::getline(in, item, ','))
    if (!item.empty()) o.schedules.push_back(learning::parseFusionSchedule(item));
  if (o.schedules.empty()) throw Error("--fusion-schedule: no schedule given");
  return o;
}

void FusionFlags::addStopBelief(CLI::App& cmd) {
  cmd.add_option("--stop-belief", fusion.stop_belief,
                 "Stop a sequence once the highest fused belief reaches this")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
}

void FusionFlags::addEvaluationOptions(CLI::App& cmd) {
  cmd.add_option("--fusion-views", views, "Protocol fusion: sequences of 1 … N views")
      ->check(CLI::Range(1, 72))
      ->capture_default_str();
  cmd.add_option("--fusion-schedule", schedules,
                 "Protocol fusion: how a sequence's views are spread, comma-separated: DEG (n views evenly over DEG "
                 "degrees), stepDEG (DEG apart); the first also measures the stopping rule")
      ->capture_default_str();
  addStopBelief(cmd);
}

int runFusionEvaluate(const FusionEvaluateArgs& a) {
  if (learning::featureSetChoices(a.features).size() != 1 || a.features.find(',') != std::string::npos ||
      a.features.find(' ') != std::string::npos)
    throw Error("--protocol fusion measures one feature set: give --features one ('+' concatenates blocks), not '" +
                a.features + "'");
  if (a.classifier.find(',') != std::string::npos)
    throw Error("--protocol fusion measures one classifier: give --classifier xgboost or mlp, not '" + a.classifier + "'");
  const learning::FusionEvaluationOptions options = a.flags.evaluationOptions();
  const learning::FeatureTable t = datasetFeatures(a.dataset, a.options, a.jobs, a.quiet);
  const std::map<std::string, double> poses = dataset::datasetAzimuths(a.dataset);
  std::vector<double> azimuths;
  std::set<std::string> elevations;
  std::map<std::string, std::set<std::string>> instances;
  for (const auto& row : t.rows) {
    const auto it = poses.find(row.id);
    azimuths.push_back(it == poses.end() ? std::nan("") : it->second);
    elevations.insert(row.elevation);
    instances[row.cls].insert(row.instance);
  }
  std::vector<std::string> protocols;
  for (const auto& [cls, inst] : instances)
    if (inst.size() > 1) {
      protocols.push_back("leave-instance");
      break;
    }
  if (elevations.size() > 1) protocols.push_back("leave-elevation");
  if (protocols.empty())
    throw Error(a.dataset + ": no category has two instances and every view has one elevation: the fusion protocol "
                "needs leave-instance or leave-elevation folds");
  learning::ClassifierParams params = a.params;
  params.kind = a.classifier;
  const auto blocks = learning::featureSetBlocks(a.features);
  std::vector<learning::FusionProtocolResult> results;
  for (const auto& p : protocols) {
    if (!a.quiet) std::cerr << "keyturn evaluate: fusion under " << p << "\n";
    results.push_back(learning::evaluateFusion(t, azimuths, blocks, p, params, options, a.jobs));
  }
  const learning::FusionReport report = learning::fusionReport(results, a.dataset, a.features, a.classifier, options);
  const std::filesystem::path out(a.out);
  writeReportFiles(a.out, report);
  if (a.json) std::cout << report.json;
  if (!a.quiet) std::cerr << "keyturn evaluate: fusion → " << (out / "report.md").string() << "\n";
  return 0;
}

}  // namespace keyturn::app
