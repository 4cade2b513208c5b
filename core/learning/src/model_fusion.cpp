#include "keyturn/learning/model_fusion.h"

#include <algorithm>
#include <cmath>

#include "keyturn/core/error.h"
#include "keyturn/learning/turn_fusion.h"

namespace keyturn::learning {

void addPoseReferences(Model& m, const FeatureTable& t, const std::vector<double>& az, LabelKind kind, double bin_deg) {
  if (az.size() != t.rows.size())
    throw Error("pose references: " + std::to_string(t.rows.size()) + " views but " + std::to_string(az.size()) + " azimuths");
  std::vector<std::size_t> rows;
  std::vector<int> y;
  std::vector<double> azimuths;
  std::vector<std::string> groups;
  const auto& classes = m.info.classes;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto& r = t.rows[i];
    if (r.keypoints < 0 && !r.problem.empty()) continue;  // not described: not trained on either
    const std::string& label = kind == LabelKind::Category ? r.cls : r.instance;
    const auto c = std::find(classes.begin(), classes.end(), label);
    if (c == classes.end()) throw Error("pose references: view " + r.id + " is labelled '" + label + "', not a class of the model");
    if (!std::isfinite(az[i])) throw Error("pose references: view " + r.id + " has no azimuth");
    rows.push_back(i);
    y.push_back(static_cast<int>(c - classes.begin()));
    azimuths.push_back(az[i]);
    groups.push_back(r.instance + "/" + r.elevation);
  }
  m.info.pose_references = fitPoseReferences(t.select(m.info.blocks, rows), y, azimuths, groups,
                                             static_cast<int>(classes.size()), bin_deg);
}

ModelFusion fusePredictions(const Model& m, const FeatureTable& t, const std::vector<Prediction>& preds,
                            const std::vector<double>& az, const FusionOptions& o) {
  checkFusionMethod(o.method);
  if (az.size() != preds.size())
    throw Error("fusion: " + std::to_string(preds.size()) + " views but " + std::to_string(az.size()) + " azimuths");
  const bool pose = o.method == "pose";
  if (pose && m.info.pose_references.empty())
    throw Error("fusion: the model holds no pose references (trained without the views' poses): fuse independently");
  if (std::all_of(preds.begin(), preds.end(), [](const Prediction& p) { return p.answer == Answer::NoObject; }))
    throw Error("fusion: none of the sequence's views could be described");
  ModelFusion out;
  out.method = o.method;
  TurnFusion turn(o, m.info.open_set);
  const std::size_t classes = m.info.classes.size();
  for (std::size_t i = 0; i < preds.size(); ++i) {
    const Prediction& p = preds[i];
    TurnView v{p.answer, p.score, p.probabilities, az[i], {}};
    if (pose && p.answer != Answer::NoObject) v.pose = poseEvidence(m.info.pose_references, t.select(m.info.blocks, {p.row}).row(0));
    turn.add(v);
    FusedStep s;
    s.row = p.row;
    s.azimuth_deg = az[i];
    s.view_answer = p.answer;
    s.belief = turn.belief();
    if (s.belief.empty()) s.belief.assign(classes, 1.0 / static_cast<double>(std::max<std::size_t>(1, classes)));
    s.best = turn.best();
    s.answer = turn.answer();
    if (out.stopped_after == 0) {
      if (turn.certain()) out.stopped_after = i + 1;
      else if (turn.certainWhileUnknown() && out.certain_while_unknown == 0) out.certain_while_unknown = i + 1;
    }
    out.steps.push_back(std::move(s));
  }
  return out;
}

}  // namespace keyturn::learning
