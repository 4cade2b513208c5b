// keyturn classify --fuse: the views of one object, taken as the turntable turned it, fused into
// the belief after each view (learning/model_fusion.h); the poses come from the dataset's
// manifest (--object) or from each view's sidecar. With --turns, every turn of a dataset
// (learning::turnsOf), each fused alone: a model's answers over turns, as evaluate reads them.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cached_features.h"
#include "fusion_options.h"
#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"
#include "keyturn/core/view_files.h"
#include "keyturn/learning/model_fusion.h"
#include "keyturn/learning/turn_fusion.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/dataset_views.h"
#include "keyturn/dataset/view_poses.h"

namespace keyturn::app {
namespace {

struct PosedViews {
  std::vector<learning::LabelledView> views;
  std::vector<double> azimuths;  // NaN where not read (independent fusion needs none)
};

// --object CLASS/INSTANCE[/ELEVATION] of a dataset: its views in capture order, posed by the manifest.
PosedViews datasetObject(const std::string& root, const std::string& object, const std::vector<double>& wanted,
                         const DepthImageOptions& depth) {
  const auto a = object.find('/');
  const auto b = a == std::string::npos ? a : object.find('/', a + 1);
  if (a == std::string::npos || a == 0 || a + 1 == object.size() || b + 1 == object.size())
    throw Error("--object: '" + object + "' is not CLASS/INSTANCE or CLASS/INSTANCE/ELEVATION");
  const std::string cls = object.substr(0, a);
  const std::string instance = object.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
  std::string elevation = b == std::string::npos ? "" : object.substr(b + 1);
  if (elevation.size() > 1 && elevation[0] == 'e') elevation.erase(0, 1);  // the folder's name, e45, names label 45
  std::vector<dataset::ViewRecord> records;
  const auto views = dataset::datasetViews(root, nullptr, &records);
  PosedViews out;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const auto& v = views[i];
    if (v.cls != cls || v.instance != instance || (!elevation.empty() && v.elevation != elevation)) continue;
    const double az = records[i].measured_deg;
    if (!wanted.empty() && std::none_of(wanted.begin(), wanted.end(), [az](double w) {
          const double d = std::fmod(std::fabs(az - w), 360.0);
          return std::min(d, 360.0 - d) <= 2.5;
        }))
      continue;
    learning::LabelledView lv = v;
    lv.depth = depth;
    out.views.push_back(lv);
    out.azimuths.push_back(az);
  }
  if (out.views.empty())
    throw Error(root + ": no view of " + object + (wanted.empty() ? std::string() : " at the azimuths asked for"));
  return out;
}

nlohmann::json beliefJson(const learning::ModelInfo& m, const std::vector<double>& belief) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t c = 0; c < belief.size() && c < m.classes.size(); ++c) j[m.classes[c]] = belief[c];
  return j;
}

std::string fusedLabel(const learning::ModelInfo& m, const learning::FusedStep& s) {
  return s.answer == learning::Answer::Class ? m.classes.at(static_cast<std::size_t>(s.best)) : learning::answerName(s.answer);
}

// A view that could not be read or described stops the sequences in one line naming it; one too empty to
// be an object is answered "no object" instead and fusion leaves it out (turn_fusion.h).
void refuseUndescribedViews(const learning::FeatureTable& t) {
  for (const auto& row : t.rows)
    if (row.keypoints < 0 && !row.problem.empty() && !row.no_object) throw Error(row.id + ": " + row.problem);
}

// --turns: the dataset's views described and classified once, then every turn fused alone.
int classifyTurns(const ClassifyFusionArgs& a, const learning::Model& m, const learning::FusionOptions& options,
                  const DepthImageOptions& depth) {
  if (a.inputs.size() != 1 || !isDataset(a.inputs[0]))
    throw Error("--turns reads the turns of one dataset folder (manifest.csv), not of " + std::to_string(a.inputs.size()) +
                " inputs");
  if (!a.object.empty() || !a.azimuths.empty()) throw Error("--turns takes every object's turns: leave out --object and --azimuths");
  std::vector<dataset::ViewRecord> records;
  std::vector<learning::LabelledView> views = dataset::datasetViews(a.inputs[0], nullptr, &records);
  std::vector<double> az;
  std::vector<std::string> group;
  for (std::size_t i = 0; i < views.size(); ++i) {
    views[i].depth = depth;
    az.push_back(records[i].measured_deg);
    group.push_back(views[i].cls + "/" + views[i].instance + "/e" + views[i].elevation);
  }
  const std::vector<std::vector<int>> turns = learning::turnsOf(az, group);
  if (turns.empty())
    throw Error(a.inputs[0] + ": no turn of " + std::to_string(learning::kTurnViews) + " views over " +
                std::to_string(static_cast<int>(learning::kTurnSpreadDeg)) + "° in any object's views");
  DescribeProgressLine progress(a.quiet);
  const learning::FeatureTable t = learning::describeForModel(m, views, a.jobs, &progress, a.model);
  refuseUndescribedViews(t);
  const auto preds = learning::predictRows(m, t, a.model);
  std::vector<const learning::Prediction*> of_view(views.size(), nullptr);
  for (const auto& p : preds) of_view.at(p.row) = &p;
  nlohmann::json out = nlohmann::json::array();
  if (!a.json) std::cout << "# object\tstart\tviews' answers\tfused (" << options.method << ")\n";
  for (const auto& seq : turns) {
    std::vector<learning::Prediction> turn_preds;
    std::vector<double> turn_az;
    std::vector<std::string> ids, answers;
    for (int i : seq) {
      const auto* p = of_view.at(static_cast<std::size_t>(i));
      if (!p) throw Error(views[static_cast<std::size_t>(i)].id + ": not classified");
      turn_preds.push_back(*p);
      turn_az.push_back(az[static_cast<std::size_t>(i)]);
      ids.push_back(t.rows[p->row].id);
      answers.push_back(learning::answerLabel(m.info, *p));
    }
    const learning::ModelFusion fused = learning::fusePredictions(m, t, turn_preds, turn_az, options);
    const learning::FusedStep& last = fused.steps.back();
    const std::string& object = group[static_cast<std::size_t>(seq.front())];
    if (a.json)
      out.push_back({{"object", object}, {"start_deg", turn_az.front()}, {"views", ids}, {"view_classes", answers},
                     {"class", fusedLabel(m.info, last)}, {"answer", learning::answerName(last.answer)}});
    else {
      std::cout << object << "\t" << std::fixed << std::setprecision(1) << turn_az.front() << "\t";
      for (std::size_t k = 0; k < answers.size(); ++k) std::cout << (k ? "," : "") << answers[k];
      std::cout << "\t" << fusedLabel(m.info, last) << "\n";
    }
  }
  if (a.json) std::cout << nlohmann::json{{"method", options.method}, {"turns", out}}.dump(2) << "\n";
  return 0;
}

}  // namespace

int runClassifyFused(const ClassifyFusionArgs& a, const DepthImageOptions& depth) {
  learning::FusionOptions options = a.flags.fusion;
  learning::checkFusionMethod(options.method);
  const learning::Model m = learning::loadModel(a.model);
  if (options.method == "pose" && m.info.pose_references.empty()) {
    if (!a.quiet)
      std::cerr << "keyturn classify: " << a.model
                << " holds no pose references (trained before them, or on views without poses): fusing independently\n";
    options.method = "independent";
  }
  if (a.turns) return classifyTurns(a, m, options, depth);
  const bool need_poses = options.method == "pose";
  PosedViews posed;
  if (!a.object.empty()) {
    if (a.inputs.size() != 1 || !isDataset(a.inputs[0]))
      throw Error("--object picks an object of one dataset folder (manifest.csv), not of " + std::to_string(a.inputs.size()) + " inputs");
    posed = datasetObject(a.inputs[0], a.object, a.azimuths.empty() ? std::vector<double>() : parseNumberList(a.azimuths, "--azimuths"), depth);
  } else {
    if (!a.azimuths.empty()) throw Error("--azimuths picks views of a dataset's --object");
    ViewFileList list = collectViewFiles(a.inputs, depth.intrinsics.has_value());
    if (!list.errors.empty()) throw Error(list.errors.front());
    for (const auto& f : list.files) {
      posed.views.push_back({f, f, "?", "?", "?", depth});
      // A view without a pose is an error for pose fusion (the method needs every angle).
      posed.azimuths.push_back(need_poses ? dataset::readViewAzimuth(dataset::sidecarPathOf(f)) : std::nan(""));
    }
  }
  DescribeProgressLine progress(a.quiet || posed.views.size() < 2);
  const learning::FeatureTable t = learning::describeForModel(m, posed.views, a.jobs, &progress, a.model);
  refuseUndescribedViews(t);
  const auto preds = learning::predictRows(m, t, a.model);
  std::vector<double> az;
  for (const auto& p : preds) az.push_back(std::isfinite(posed.azimuths[p.row]) ? posed.azimuths[p.row] : 0.0);
  const learning::ModelFusion fused = learning::fusePredictions(m, t, preds, az, options);

  if (a.json) {
    nlohmann::json steps = nlohmann::json::array();
    for (std::size_t i = 0; i < fused.steps.size(); ++i) {
      const auto& s = fused.steps[i];
      const auto& p = preds[i];
      steps.push_back({{"view", t.rows[s.row].id},
                       {"azimuth_deg", std::isfinite(posed.azimuths[s.row]) ? nlohmann::json(s.azimuth_deg) : nullptr},
                       {"view_class", learning::answerLabel(m.info, p)},
                       {"view_answer", learning::answerName(p.answer)},
                       {"view_probability", p.best >= 0 ? nlohmann::json(p.probabilities[static_cast<std::size_t>(p.best)]) : nullptr},
                       {"class", fusedLabel(m.info, s)},
                       {"answer", learning::answerName(s.answer)},
                       {"belief", s.best >= 0 ? nlohmann::json(s.belief[static_cast<std::size_t>(s.best)]) : nullptr},
                       {"beliefs", beliefJson(m.info, s.belief)}});
    }
    std::cout << nlohmann::json{{"method", fused.method},
                                {"stop_belief", options.stop_belief},
                                {"stopped_after", fused.stopped_after ? nlohmann::json(fused.stopped_after) : nullptr},
                                {"views", steps}}
                     .dump(2)
              << "\n";
    return 0;
  }
  std::cout << "# view\tazimuth\tthis view\tp\tfused (" << fused.method << ")\tbelief\n";
  for (std::size_t i = 0; i < fused.steps.size(); ++i) {
    const auto& s = fused.steps[i];
    const auto& p = preds[i];
    std::cout << t.rows[s.row].id << "\t";
    if (std::isfinite(posed.azimuths[s.row])) std::cout << std::fixed << std::setprecision(1) << s.azimuth_deg;
    else std::cout << "-";
    std::cout << "\t" << learning::answerLabel(m.info, p) << "\t" << std::setprecision(3);
    if (p.best >= 0) std::cout << p.probabilities[static_cast<std::size_t>(p.best)];
    else std::cout << "-";
    std::cout << "\t" << fusedLabel(m.info, s) << "\t";
    if (s.best >= 0) std::cout << s.belief[static_cast<std::size_t>(s.best)];
    else std::cout << "-";
    if (fused.stopped_after == i + 1) std::cout << "\tcertain (>= " << options.stop_belief << ")";
    std::cout << "\n";
  }
  if (!a.quiet && fused.stopped_after == 0) {
    std::cerr << "keyturn classify: ";
    if (fused.steps.empty() || fused.steps.back().best < 0)  // no view added evidence: there is no belief to speak of
      std::cerr << "no view was answered with one of the model's classes, so there was no belief to fuse\n";
    else if (fused.certain_while_unknown)  // the belief is over the model's classes, the answer none of them
      std::cerr << "no class became certain: the fused belief over the model's classes reached " << options.stop_belief
                << " (first at view " << fused.certain_while_unknown
                << ") only where the fused answer was unknown (the mean open-set score of the views so far under the model's threshold)\n";
    else
      std::cerr << "the fused belief never reached " << options.stop_belief << "\n";
  }
  return 0;
}

}  // namespace keyturn::app
