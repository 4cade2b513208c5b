// keyturn train / keyturn classify: a model trained on a whole dataset, saved
// with its feature specification, and applied to new views (or to a feature
// cache). Features computed another way than the model's are refused.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "cached_features.h"
#include "depth_image_options.h"
#include "descriptor_options.h"
#include "fusion_options.h"
#include "keyturn/learning/model_fusion.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_training.h"
#include "keyturn/learning/turn_fusion.h"
#include "learning_options.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/view_files.h"
#include "keyturn/dataset/view_poses.h"

namespace keyturn::app {
namespace {

struct TrainArgs {
  // The set that did best across protocols on real and simulated views (docs/results.md, "Sim-to-real")
  std::vector<std::string> datasets;  // trained on together (e.g. one per camera, keyturn simulate --camera)
  std::string features = "kpa3+s_kpd2", classifier = "xgboost", label = "instance", out;
  int jobs = 0;
  bool quiet = false;
  DescriptorFlags flags;
  learning::ClassifierParams params;
  learning::OpenSetOptions open_set;
  std::string open_set_method = "none";  // closed-set unless asked (docs/results.md, "Open-set answers")
};

// Each row's turntable angle from its dataset's manifest (NaN where it has none).
std::vector<double> datasetRowAzimuths(const std::string& dataset, const learning::FeatureTable& t) {
  const auto poses = dataset::datasetAzimuths(dataset);
  std::vector<double> azimuths;
  for (const auto& row : t.rows) {
    const auto it = poses.find(row.id);
    azimuths.push_back(it == poses.end() ? std::nan("") : it->second);
  }
  return azimuths;
}

// Each row's camera (cameraOf: the organized grid), for the open-set camera scale: a dataset is one
// camera's views (keyturn simulate --camera, capture), so its first view tells it. The feature cache
// does not keep it.
void setDatasetCamera(const std::string& dataset, learning::FeatureTable& t, std::size_t from) {
  const std::vector<dataset::LabelledView> views = datasetViews(dataset);
  const std::string camera = learning::cameraOf(loadCloud(views.front().path, views.front().depth));
  for (std::size_t r = from; r < t.rows.size(); ++r) t.rows[r].camera = camera;
}

int runTrain(const TrainArgs& a) {
  const learning::LabelKind kind = learning::parseLabelKind(a.label);
  learning::OpenSetOptions open_set = a.open_set;
  setOpenSetFlag(open_set, a.open_set_method);  // before describing: a wrong name fails at once
  learning::FeatureTable t = datasetFeatures(a.datasets.front(), a.flags.options, a.jobs, a.quiet, {a.features});
  std::vector<double> azimuths = datasetRowAzimuths(a.datasets.front(), t);
  setDatasetCamera(a.datasets.front(), t, 0);
  for (std::size_t d = 1; d < a.datasets.size(); ++d) {
    const learning::FeatureTable more = datasetFeatures(a.datasets[d], a.flags.options, a.jobs, a.quiet, {a.features});
    const std::size_t from = t.rows.size();
    learning::appendRows(t, more, a.datasets[d]);
    setDatasetCamera(a.datasets[d], t, from);
    const std::vector<double> more_azimuths = datasetRowAzimuths(a.datasets[d], more);
    azimuths.insert(azimuths.end(), more_azimuths.begin(), more_azimuths.end());
  }
  learning::ClassifierParams params = a.params;
  params.kind = a.classifier;
  double s = 0;
  learning::Model m = learning::trainModel(t, learning::featureSetBlocks(a.features), kind, params, &s, open_set, azimuths);
  // Pose fusion's references (classify --fuse), when every view has its turntable angle.
  const bool posed = std::all_of(azimuths.begin(), azimuths.end(), [](double v) { return std::isfinite(v); });
  if (posed) learning::addPoseReferences(m, t, azimuths, kind, learning::FusionOptions().bin_deg);
  learning::saveModel(a.out, m);
  if (!a.quiet) {
    std::cerr << "keyturn train: " << a.classifier << " on " << a.features << ", " << t.rows.size() << " views";
    if (a.datasets.size() > 1) std::cerr << " of " << a.datasets.size() << " datasets";
    std::cerr << ", "
              << m.info.classes.size() << " classes, " << std::fixed << std::setprecision(1) << s << " s";
    const learning::OpenSet& os = m.info.open_set;
    std::cerr << openSetSummary(os);
    if (!std::isfinite(os.turn_threshold) && !open_set.methods.empty())
      std::cerr << "; closed-set (open-set calibration leaves categories out: it needs at least "
                << learning::kOpenSetMinCategories << " categories)";
    std::cerr << (posed ? "; pose references for fusion" : "; no pose references (a view without its turntable angle)");
    std::cerr << " → " << a.out << "\n";
  }
  return 0;
}

// One view's answer as classify --json gives it: "class" is the answer's label (a class, "unknown"
// or "no object"), "best" the most probable class; "score" and "threshold" the open-set test (null
// for a closed-set model).
nlohmann::json predictionJson(const learning::ModelInfo& m, const learning::Prediction& p, const learning::FeatureRow& row) {
  nlohmann::json probs = nlohmann::json::object();
  for (std::size_t c = 0; c < p.probabilities.size() && c < m.classes.size(); ++c) probs[m.classes[c]] = p.probabilities[c];
  const bool described = p.best >= 0;
  const bool open = m.open_set.enabled() && described;
  nlohmann::json j = {{"view", row.id},
                      {"class", learning::answerLabel(m, p)},
                      {"answer", learning::answerName(p.answer)},
                      {"best", described ? nlohmann::json(m.classes.at(static_cast<std::size_t>(p.best))) : nullptr},
                      {"probability", described ? nlohmann::json(p.probabilities[static_cast<std::size_t>(p.best)]) : nullptr},
                      {"open_set", m.open_set.enabled() ? nlohmann::json(m.open_set.method) : nullptr},
                      {"score", open && std::isfinite(p.score) ? nlohmann::json(p.score) : nullptr},
                      {"threshold", m.open_set.enabled() ? nlohmann::json(m.open_set.threshold) : nullptr},
                      {"keypoints", row.keypoints},
                      {"probabilities", probs}};
  if (p.answer == learning::Answer::NoObject) j["problem"] = row.problem;
  return j;
}

struct ClassifyArgs {
  std::string model;
  std::vector<std::string> inputs;
  bool json = false, quiet = false, fuse = false;
  int jobs = 0;
  DepthImageFlags depth;
  ClassifyFusionArgs fusion;  // --fuse
};

int runClassify(const ClassifyArgs& a) {
  if (!a.fuse && (!a.fusion.object.empty() || !a.fusion.azimuths.empty() || a.fusion.turns))
    throw Error("--object, --azimuths and --turns pick the views of fused sequences: give --fuse");
  if (a.fuse) {
    ClassifyFusionArgs f = a.fusion;
    f.model = a.model, f.inputs = a.inputs, f.json = a.json, f.quiet = a.quiet, f.jobs = a.jobs;
    return runClassifyFused(f, a.depth.toOptions());
  }
  const learning::Model m = learning::loadModel(a.model);
  learning::FeatureTable t;
  std::vector<std::string> errors;
  if (a.inputs.size() == 1 && a.inputs[0].size() > 4 && a.inputs[0].compare(a.inputs[0].size() - 4, 4, ".csv") == 0) {
    t = learning::loadFeatureTable(a.inputs[0]);
  } else {
    const DepthImageOptions depth = a.depth.toOptions();
    ViewFileList list = collectViewFiles(a.inputs, depth.intrinsics.has_value());
    errors = list.errors;
    std::vector<dataset::LabelledView> views;
    for (const auto& f : list.files) views.push_back({f, f, "?", "?", "?", depth});
    DescribeProgressLine progress(a.quiet || views.size() < 2);
    t = learning::describeForModel(m, views, a.jobs, &progress, a.model);
    for (const auto& row : t.rows)  // a view too empty to describe is answered "no object" instead
      if (row.keypoints < 0 && !row.problem.empty() && !row.no_object) errors.push_back(row.id + ": " + row.problem);
  }
  nlohmann::json js = nlohmann::json::array();
  const learning::OpenSet& os = m.info.open_set;
  for (const auto& p : learning::predictRows(m, t, a.model)) {
    const auto& row = t.rows[p.row];
    js.push_back(predictionJson(m.info, p, row));
    if (a.json) continue;
    std::cout << row.id << "\t" << learning::answerLabel(m.info, p) << "\t" << std::fixed << std::setprecision(3);
    if (p.best >= 0) std::cout << p.probabilities[static_cast<std::size_t>(p.best)];
    else std::cout << "-";
    std::cout << "\tK=" << row.keypoints;
    if (os.enabled() && p.answer != learning::Answer::NoObject)
      std::cout << "\t" << os.method << " " << std::setprecision(4) << p.score
                << (p.answer == learning::Answer::Class ? " >= " : " < ") << os.threshold << " ("
                << m.info.classes.at(static_cast<std::size_t>(p.best)) << ")";
    if (p.answer == learning::Answer::NoObject) std::cout << "\t" << row.problem;
    std::cout << "\n";
  }
  if (a.json) std::cout << js.dump(2) << "\n";
  for (const auto& e : errors) std::cerr << "keyturn classify: " << e << "\n";
  return errors.empty() ? 0 : 1;
}

}  // namespace

Command addTrainCommand(CLI::App& app) {
  auto a = std::make_shared<TrainArgs>();
  auto* cmd = app.add_subcommand("train", "Train a classifier on a whole dataset and save it with its feature spec");
  cmd->add_option("datasets", a->datasets,
                  "Dataset folders, trained on together: e.g. the same objects through each camera (keyturn simulate "
                  "--camera sr4000 and openni2)")
      ->required();
  cmd->add_option("--features", a->features, "Feature set ('+' concatenates blocks)")->capture_default_str();
  cmd->add_option("--classifier", a->classifier, "xgboost, mlp or setnet (a set network over the keypoints: features kpset or kpset+…)")->capture_default_str();
  cmd->add_option("--label", a->label, "instance or category")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Model folder")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views when describing");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->flags.add(*cmd, false);
  addClassifierOptions(*cmd, a->params);
  addOpenSetOptions(*cmd, a->open_set, &a->open_set_method);
  return {cmd, [a] { return runTrain(*a); }};
}

Command addClassifyCommand(CLI::App& app) {
  auto a = std::make_shared<ClassifyArgs>();
  auto* cmd = app.add_subcommand("classify", "Classify views (PCD/PLY files, depth PNGs, folders, or a feature cache CSV) with a model, described with the model's own parameters");
  cmd->add_option("model", a->model, "Model folder (from keyturn train)")->required();
  cmd->add_option("views", a->inputs, "PCD/PLY files, depth PNGs or folders, or one feature cache .csv")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views");
  cmd->add_flag("--json", a->json,
                "Answer (a class, unknown or no object), probabilities and open-set score per view as JSON");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  cmd->add_flag("--fuse", a->fuse,
                "The views are one object's as the turntable turned it: print the fused belief after each view "
                "(poses from the views' sidecars, or the dataset's manifest with --object)");
  cmd->add_option("--fusion-method", a->fusion.flags.fusion.method,
                  "pose (the classifier's evidence and the views' match to the class's training views at the same "
                  "relative angles) or independent (the classifier's probabilities multiplied; no poses needed)")
      ->check(CLI::IsMember(learning::fusionMethods()))
      ->capture_default_str();
  cmd->add_option("--object", a->fusion.object,
                  "With --fuse and a dataset folder: the views of CLASS/INSTANCE[/ELEVATION], in capture order");
  cmd->add_option("--azimuths", a->fusion.azimuths, "With --object: only the views at these angles, e.g. 0,45,90");
  cmd->add_flag("--turns", a->fusion.turns,
                "With --fuse and a dataset folder: every turn of its objects (3 views over 90°, one starting at every "
                "view of each object and elevation, as evaluate reads turns), each fused alone; one answer per turn");
  a->fusion.flags.addStopBelief(*cmd);
  a->depth.add(*cmd);
  return {cmd, [a] { return runClassify(*a); }};
}

}  // namespace keyturn::app
