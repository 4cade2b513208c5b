#include "keyturn/learning/model_enrollment.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "keyturn/core/error.h"
#include "keyturn/learning/model_fusion.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/learning/model_recalibration.h"
#include "keyturn/learning/model_training.h"
#include "reference_value_json.h"

namespace keyturn::learning {

namespace {

void checkTrainingViews(const Model& m, const std::string& source) {
  if (m.info.training_views.empty())
    throw Error(source + ": the model keeps no training views to retrain with (trained before models kept them, or "
                "closed-set): retrain it with keyturn train and a knn or knn-relative open set");
}

// Each model input's column in a table of the model's layout: the blocks in the model's order, concatenated.
std::vector<int> inputColumns(const Model& m, const FeatureTable& t, const std::string& source) {
  std::vector<int> column;
  for (const auto& b : m.info.blocks)
    for (int k = 0; k < t.blockSize(b); ++k) column.push_back(t.offset(b) + k);
  if (static_cast<int>(column.size()) != m.info.inputs || static_cast<int>(m.info.open_set.mean.size()) != m.info.inputs)
    throw Error(source + ": the model's blocks make " + std::to_string(column.size()) + " inputs, not " +
                std::to_string(m.info.inputs));
  return column;
}

// A training value as the model file gives it back: its standardised reference to 4 decimals
// (reference_value_json.h), unstandardised, and 0 where the reference is 0's. Every training row
// takes this form, the model's own views and the new object's alike: otherwise the file's rounding
// tells them apart. A PDF's tail bins are exactly 0 on most views; they came back as one constant
// of about ±7e-7 per column, the new views kept their 0, and the retrained trees split there: the
// built-in model's own objects went from 85 to 55 % named, the new object taking their views.
float keptValue(float standardised, float mean, float scale) {
  if (std::isnan(standardised)) return standardised;
  const double ref = referenceValue(standardised);
  if (ref == referenceValue((0.f - mean) / scale)) return 0.f;
  return static_cast<float>(ref * scale + mean);
}

}  // namespace

TrainingTable modelTrainingTable(const Model& m, const std::string& source) {
  checkTrainingViews(m, source);
  const OpenSet& os = m.info.open_set;
  TrainingTable out;
  out.table = modelLayout(m, source);
  FeatureTable& t = out.table;
  const std::vector<int> column = inputColumns(m, t, source);
  const auto& views = m.info.training_views.views;
  for (std::size_t r = 0; r < views.size(); ++r) {
    const TrainingView& v = views[r];
    FeatureRow row;
    row.id = "model/" + std::to_string(r);
    row.cls = v.cls, row.instance = v.instance, row.elevation = v.elevation, row.camera = v.camera;
    row.values.assign(static_cast<std::size_t>(t.width()), std::nanf(""));
    for (int k = 0; k < m.info.inputs; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      row.values[static_cast<std::size_t>(column[kk])] =
          keptValue(os.references(static_cast<Eigen::Index>(r), k), os.mean[kk], os.scale[kk]);
    }
    for (int k : v.missing) row.values[static_cast<std::size_t>(column[static_cast<std::size_t>(k)])] = std::nanf("");
    if (v.missing.size() == static_cast<std::size_t>(m.info.inputs)) row.keypoints = -1, row.problem = "not described";
    else row.keypoints = 0;  // K is not kept
    t.rows.push_back(std::move(row));
    out.azimuth_deg.push_back(v.azimuth_deg);
  }
  return out;
}

std::string enrolledClass(const Model& m, const std::string& cls, const std::string& instance, const std::string& source) {
  checkTrainingViews(m, source);
  const bool by_category = m.info.training_views.label == LabelKind::Category;
  const std::string label = by_category ? cls : instance;
  const auto& classes = m.info.classes;
  if (std::find(classes.begin(), classes.end(), label) != classes.end())
    throw Error(source + ": '" + label + "' is already a class of the model (" + std::to_string(classes.size()) +
                " classes): enroll another " + (by_category ? "category" : "instance") + " name");
  for (const auto& v : m.info.training_views.views)
    if (v.instance == instance)
      throw Error(source + ": the model was already trained on instance '" + instance + "' (class '" + v.cls + "')");
  return label;
}

Enrollment enrollObject(const Model& m, const FeatureTable& views, const std::vector<double>& azimuth_deg,
                        const std::string& source) {
  if (azimuth_deg.size() != views.rows.size())
    throw Error("enroll: " + std::to_string(views.rows.size()) + " views but " + std::to_string(azimuth_deg.size()) +
                " angles");
  std::set<std::pair<std::string, std::string>> objects;
  for (const auto& r : views.rows) objects.insert({r.cls, r.instance});
  if (objects.size() != 1)
    throw Error("enroll: the new views are of " + std::to_string(objects.size()) + " objects, not one");
  enrolledClass(m, objects.begin()->first, objects.begin()->second, source);
  TrainingTable all = modelTrainingTable(m, source);
  Enrollment out;
  out.training_views = all.table.rows.size();
  FeatureTable described = views;
  described.rows.clear();
  const std::vector<int> column = inputColumns(m, all.table, source);
  const OpenSet& os = m.info.open_set;
  for (std::size_t i = 0; i < views.rows.size(); ++i) {
    FeatureRow r = views.rows[i];
    if (r.keypoints < 0) {  // nothing to learn from; left out as the pose references leave it out
      ++out.skipped;
      continue;
    }
    if (r.values.size() != static_cast<std::size_t>(all.table.width()))
      throw Error("enroll: view " + r.id + " has " + std::to_string(r.values.size()) + " values, the model's layout " +
                  std::to_string(all.table.width()));
    for (std::size_t k = 0; k < column.size(); ++k) {
      float& v = r.values[static_cast<std::size_t>(column[k])];
      v = keptValue((v - os.mean[k]) / os.scale[k], os.mean[k], os.scale[k]);
    }
    described.rows.push_back(std::move(r));
    all.azimuth_deg.push_back(azimuth_deg[i]);
  }
  out.new_views = described.rows.size();
  if (described.rows.empty())
    throw Error("enroll: none of the object's " + std::to_string(views.rows.size()) + " views could be described");
  appendRows(all.table, described, "the object's views");

  const ModelInfo& info = m.info;
  const OpenSetOptions o = openSetOptionsOf(m);
  const LabelKind kind = info.training_views.label;
  out.model = trainModel(all.table, info.blocks, kind, info.params, &out.fit_s, o, all.azimuth_deg);
  const bool posed = std::all_of(all.azimuth_deg.begin(), all.azimuth_deg.end(), [](double a) { return std::isfinite(a); });
  if (!info.pose_references.empty() && posed)
    addPoseReferences(out.model, all.table, all.azimuth_deg, kind, 360.0 / info.pose_references.bins);
  return out;
}

}  // namespace keyturn::learning
