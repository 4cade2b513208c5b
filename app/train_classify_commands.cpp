// keyturn train / keyturn classify: a model trained on a whole dataset, saved
// with its feature specification, and applied to new views (or to a feature
// cache). Features computed another way than the model's are refused.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>

#include "commands.h"
#include "dataset_features.h"
#include "descriptor_options.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_file.h"
#include "keyturn/learning/protocols.h"
#include "learning_options.h"
#include "view_files.h"

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
  const learning::Labels labels = learning::labelRows(t, kind);
  learning::Model m;
  m.info.params = a.params;
  m.info.params.kind = a.classifier;
  m.info.blocks = featureSetBlocks(a.features);
  m.info.spec = t.spec;
  m.info.classes = labels.names;
  const std::vector<int>& y = labels.of_row;
  std::vector<std::size_t> all(t.rows.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const learning::Matrix x = t.select(m.info.blocks, all);
  m.info.inputs = static_cast<int>(x.cols());
  m.info.class_means = learning::classMeans(x, y, static_cast<int>(m.info.classes.size()));
  m.classifier = learning::makeClassifier(m.info.params);
  const auto t0 = std::chrono::steady_clock::now();
  m.classifier->fit(x, y, static_cast<int>(m.info.classes.size()));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
};

int runClassify(const ClassifyArgs& a) {
  const learning::Model m = learning::loadModel(a.model);
  learning::FeatureTable t;
  std::vector<std::string> errors;
  if (a.inputs.size() == 1 && a.inputs[0].size() > 4 && a.inputs[0].compare(a.inputs[0].size() - 4, 4, ".csv") == 0) {
    t = learning::loadFeatureTable(a.inputs[0]);
  } else {
    ViewFileList list = collectViewFiles(a.inputs);
    errors = list.errors;
    std::vector<learning::LabelledView> views;
    for (const auto& f : list.files) views.push_back({f, f, "?", "?", "?"});
    // The model's own parameters, and only its blocks.
    const DescriptorOptions options = learning::descriptorOptionsFromSpec(m.info.spec, a.model + "/model.json");
    std::vector<std::string> blocks;
    for (const auto& b : m.info.blocks)
      if (std::find(blocks.begin(), blocks.end(), b) == blocks.end()) blocks.push_back(b);
    DescribeProgressLine progress(a.quiet || views.size() < 2);
    t = learning::featureLayout(blocks, options);
    t.rows = learning::describeViews(views, options, t, a.jobs, &progress);
    for (const auto& row : t.rows)
      if (row.keypoints < 0 && !row.problem.empty()) errors.push_back(row.id + ": " + row.problem);
  }
  const auto diff = learning::specDifferences(m.info.spec, t.spec);
  if (!diff.empty()) {
    std::string msg = a.model + ": the model was trained on features computed another way (";
    for (std::size_t i = 0; i < diff.size(); ++i) msg += (i ? "; " : "") + diff[i];
    throw Error(msg + "): describe the views with the model's parameters");
  }
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    if (t.rows[i].keypoints >= 0 || t.rows[i].problem.empty()) usable.push_back(i);
  nlohmann::json js = nlohmann::json::array();
  if (!usable.empty()) {
    const learning::Matrix p = m.classifier->predictProba(t.select(m.info.blocks, usable));
    for (std::size_t k = 0; k < usable.size(); ++k) {
      const auto& row = t.rows[usable[k]];
      Eigen::Index best = 0;
      p.row(static_cast<Eigen::Index>(k)).maxCoeff(&best);
      nlohmann::json probs;
      for (std::size_t c = 0; c < m.info.classes.size(); ++c) probs[m.info.classes[c]] = p(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c));
      js.push_back({{"view", row.id}, {"class", m.info.classes[static_cast<std::size_t>(best)]},
                    {"probability", p(static_cast<Eigen::Index>(k), best)}, {"keypoints", row.keypoints},
                    {"probabilities", probs}});
      if (!a.json)
        std::cout << row.id << "\t" << m.info.classes[static_cast<std::size_t>(best)] << "\t" << std::fixed
                  << std::setprecision(3) << p(static_cast<Eigen::Index>(k), best) << "\tK=" << row.keypoints << "\n";
    }
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
  auto* cmd = app.add_subcommand("classify", "Classify views (PCD/PLY files, folders, or a feature cache CSV) with a model, described with the model's own parameters");
  cmd->add_option("model", a->model, "Model folder (from keyturn train)")->required();
  cmd->add_option("views", a->inputs, "PCD/PLY files or folders, or one feature cache .csv")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views");
  cmd->add_flag("--json", a->json, "Class and probabilities per view as JSON");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  return {cmd, [a] { return runClassify(*a); }};
}

}  // namespace keyturn::app
