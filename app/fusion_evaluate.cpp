// keyturn evaluate --protocol fusion: accuracy against the number of views of one object, per
// fusion method and schedule, with the shuffled-poses control, under leave-instance and
// leave-elevation where the dataset has them (learning/fusion_evaluation.h runs and reports it).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>

#include "cached_features.h"
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

learning::NbvEvaluationOptions FusionFlags::nbvOptions() const {
  learning::NbvEvaluationOptions o;
  o.fusion = fusion;
  o.fusion.method = "pose";
  o.max_views = views;
  o.candidate_step_deg = nbv_step;
  o.start_every = nbv_start_every;
  o.likelihood_window_deg = nbv_window;
  std::string item;
  std::stringstream in(schedule_option_ && schedule_option_->count() ? schedules : std::string("step45"));
  while (std::getline(in, item, ','))
    if (!item.empty()) {
      o.fixed.push_back(learning::parseFusionSchedule(item));
      if (o.fixed.back().spread_deg > 0)  // a spread's first n views are not its n-view sequence
        throw Error("--fusion-schedule " + item + ": protocol nbv compares fixed steps, stepDEG (step45: 3 views over 90°)");
    }
  if (o.fixed.empty()) throw Error("--fusion-schedule: no schedule given");
  if (views < 2) throw Error("--fusion-views " + std::to_string(views) + ": next best view needs sequences of 2 or more views");
  o.target_views = std::min(3, views);
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
  schedule_option_ = cmd.add_option("--fusion-schedule", schedules,
                 "Protocol fusion: how a sequence's views are spread, comma-separated: DEG (n views evenly over DEG "
                 "degrees), stepDEG (DEG apart); the first also measures the stopping rule. Protocol nbv: the fixed "
                 "steps compared (default step45: 3 views over 90°)")
      ->capture_default_str();
  addStopBelief(cmd);
  cmd.add_option("--nbv-step", nbv_step, "Protocol nbv: the turns next best view may choose, every DEG from the first view")
      ->check(CLI::Range(1.0, 179.0))
      ->capture_default_str();
  cmd.add_option("--nbv-window", nbv_window,
                 "Protocol nbv: the per-angle confusions average the training views within DEG of each angle")
      ->check(CLI::Range(1.0, 360.0))
      ->capture_default_str();
  cmd.add_option("--nbv-start-every", nbv_start_every,
                 "Protocol nbv: sequences start at every k-th view of a held-out object (1: every view)")
      ->check(CLI::Range(1, 72))
      ->capture_default_str();
}

void checkOneFeatureSetAndClassifier(const FusionEvaluateArgs& a, const std::string& protocol) {
  if (learning::featureSetChoices(a.features).size() != 1 || a.features.find(',') != std::string::npos ||
      a.features.find(' ') != std::string::npos)
    throw Error("--protocol " + protocol + " measures one feature set: give --features one ('+' concatenates blocks), not '" +
                a.features + "'");
  if (a.classifier.find(',') != std::string::npos)
    throw Error("--protocol " + protocol + " measures one classifier: give --classifier xgboost, mlp or setnet, not '" +
                a.classifier + "'");
}

PosedTable posedTable(const FusionEvaluateArgs& a, const std::string& protocol) {
  PosedTable v;
  v.table = datasetFeatures(a.dataset, a.options, a.jobs, a.quiet, {a.features});
  const std::map<std::string, double> poses = dataset::datasetAzimuths(a.dataset);
  std::set<std::string> elevations;
  std::map<std::string, std::set<std::string>> instances;
  for (const auto& row : v.table.rows) {
    const auto it = poses.find(row.id);
    v.azimuths.push_back(it == poses.end() ? std::nan("") : it->second);
    elevations.insert(row.elevation);
    instances[row.cls].insert(row.instance);
  }
  for (const auto& [cls, inst] : instances)
    if (inst.size() > 1) {
      v.protocols.push_back("leave-instance");
      break;
    }
  if (elevations.size() > 1) v.protocols.push_back("leave-elevation");
  if (v.protocols.empty())
    throw Error(a.dataset + ": no category has two instances and every view has one elevation: the " + protocol +
                " protocol needs leave-instance or leave-elevation folds");
  return v;
}

int runFusionEvaluate(const FusionEvaluateArgs& a) {
  checkOneFeatureSetAndClassifier(a, "fusion");
  const learning::FusionEvaluationOptions options = a.flags.evaluationOptions();
  const PosedTable posed = posedTable(a, "fusion");
  const learning::FeatureTable& t = posed.table;
  const std::vector<double>& azimuths = posed.azimuths;
  const std::vector<std::string>& protocols = posed.protocols;
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
