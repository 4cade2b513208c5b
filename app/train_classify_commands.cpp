// keyturn train / keyturn classify: a model trained on a whole dataset, saved
// with its feature specification, and applied to new views (or to a feature
// cache). Features computed another way than the model's are refused.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "dataset_features.h"
#include "depth_image_options.h"
#include "descriptor_options.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_training.h"
#include "learning_options.h"
#include "keyturn/core/view_files.h"

namespace keyturn::app {
namespace {

struct TrainArgs {
  std::string dataset, features = "kpd2+gkpd2", classifier = "xgboost", label = "instance", out;
  int jobs = 0;
  bool quiet = false;
  DescriptorFlags flags;
  learning::ClassifierParams params;
};

int runTrain(const TrainArgs& a) {
  const learning::LabelKind kind = learning::parseLabelKind(a.label);
  const learning::FeatureTable t = datasetFeatures(a.dataset, a.flags.options, a.jobs, a.quiet);
  learning::ClassifierParams params = a.params;
  params.kind = a.classifier;
  double s = 0;
  const learning::Model m = learning::trainModel(t, learning::featureSetBlocks(a.features), kind, params, &s);
  learning::saveModel(a.out, m);
  if (!a.quiet)
    std::cerr << "keyturn train: " << a.classifier << " on " << a.features << ", " << t.rows.size() << " views, "
              << m.info.classes.size() << " classes, " << std::fixed << std::setprecision(1) << s << " s → " << a.out << "\n";
  return 0;
}

struct ClassifyArgs {
  std::string model;
  std::vector<std::string> inputs;
  bool json = false, quiet = false;
  int jobs = 0;
  DepthImageFlags depth;
};

int runClassify(const ClassifyArgs& a) {
  const learning::Model m = learning::loadModel(a.model);
  learning::FeatureTable t;
  std::vector<std::string> errors;
  if (a.inputs.size() == 1 && a.inputs[0].size() > 4 && a.inputs[0].compare(a.inputs[0].size() - 4, 4, ".csv") == 0) {
    t = learning::loadFeatureTable(a.inputs[0]);
  } else {
    const DepthImageOptions depth = a.depth.toOptions();
    ViewFileList list = collectViewFiles(a.inputs, depth.intrinsics.has_value());
    errors = list.errors;
    std::vector<learning::LabelledView> views;
    for (const auto& f : list.files) views.push_back({f, f, "?", "?", "?", depth});
    DescribeProgressLine progress(a.quiet || views.size() < 2);
    t = learning::describeForModel(m, views, a.jobs, &progress, a.model);
    for (const auto& row : t.rows)
      if (row.keypoints < 0 && !row.problem.empty()) errors.push_back(row.id + ": " + row.problem);
  }
  nlohmann::json js = nlohmann::json::array();
  for (const auto& p : learning::predictRows(m, t, a.model)) {
    const auto& row = t.rows[p.row];
    const auto best = static_cast<std::size_t>(p.best);
    nlohmann::json probs;
    for (std::size_t c = 0; c < m.info.classes.size(); ++c) probs[m.info.classes[c]] = p.probabilities[c];
    js.push_back({{"view", row.id}, {"class", m.info.classes[best]}, {"probability", p.probabilities[best]},
                  {"keypoints", row.keypoints}, {"probabilities", probs}});
    if (!a.json)
      std::cout << row.id << "\t" << m.info.classes[best] << "\t" << std::fixed << std::setprecision(3)
                << p.probabilities[best] << "\tK=" << row.keypoints << "\n";
  }
  if (a.json) std::cout << js.dump(2) << "\n";
  for (const auto& e : errors) std::cerr << "keyturn classify: " << e << "\n";
  return errors.empty() ? 0 : 1;
}

}  // namespace

Command addTrainCommand(CLI::App& app) {
  auto a = std::make_shared<TrainArgs>();
  auto* cmd = app.add_subcommand("train", "Train a classifier on a whole dataset and save it with its feature spec");
  cmd->add_option("dataset", a->dataset, "Dataset folder")->required();
  cmd->add_option("--features", a->features, "Feature set ('+' concatenates blocks)")->capture_default_str();
  cmd->add_option("--classifier", a->classifier, "xgboost or mlp")->capture_default_str();
  cmd->add_option("--label", a->label, "instance or category")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Model folder")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views when describing");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->flags.add(*cmd, false);
  addClassifierOptions(*cmd, a->params);
  return {cmd, [a] { return runTrain(*a); }};
}

Command addClassifyCommand(CLI::App& app) {
  auto a = std::make_shared<ClassifyArgs>();
  auto* cmd = app.add_subcommand("classify", "Classify views (PCD/PLY files, depth PNGs, folders, or a feature cache CSV) with a model, described with the model's own parameters");
  cmd->add_option("model", a->model, "Model folder (from keyturn train)")->required();
  cmd->add_option("views", a->inputs, "PCD/PLY files, depth PNGs or folders, or one feature cache .csv")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views");
  cmd->add_flag("--json", a->json, "Class and probabilities per view as JSON");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->depth.add(*cmd);
  return {cmd, [a] { return runClassify(*a); }};
}

}  // namespace keyturn::app
