#include "keyturn/learning/model_recalibration.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "keyturn/core/error.h"
#include "keyturn/learning/model_enrollment.h"
#include "keyturn/learning/model_fusion.h"
#include "keyturn/learning/model_training.h"
#include "keyturn/learning/protocols.h"

namespace keyturn::learning {

OpenSetOptions openSetOptionsOf(const Model& m) {
  const ModelInfo& info = m.info;
  OpenSetOptions o;
  o.methods = {info.open_set.method};
  o.false_accept = info.open_set.false_accept;
  o.neighbours = info.open_set.neighbours;
  o.scale_by = info.open_set.scale_by;  // a model calibrated with the pooled scale stays pooled
  o.class_scale_power = info.open_set.class_scale_power;
  o.class_spread = info.open_set.class_spread;
  o.distance = info.open_set.distance;
  o.rule = info.open_set.rule;
  o.groups = info.training_views.open_set_groups;
  o.seed = info.training_views.open_set_seed;
  o.required = true;
  return o;
}

void recalibrateOpenSet(Model& m, const OpenSetOptions& options, const std::string& source) {
  const TrainingTable all = modelTrainingTable(m, source);
  const Labels labels = labelRows(all.table, m.info.training_views.label);
  if (labels.names != m.info.classes)
    throw Error(source + ": its kept training views name " + std::to_string(labels.names.size()) +
                " classes, not the model's " + std::to_string(m.info.classes.size()));
  std::vector<std::size_t> rows(all.table.rows.size());
  std::iota(rows.begin(), rows.end(), std::size_t{0});
  const Matrix x = all.table.select(m.info.blocks, rows);
  m.info.open_set =
      calibrateModelOpenSet(all.table, x, labels.of_row, m.info.blocks, m.info.params, options, all.azimuth_deg);
  const bool posed = std::all_of(all.azimuth_deg.begin(), all.azimuth_deg.end(), [](double a) { return std::isfinite(a); });
  if (!m.info.pose_references.empty() && posed)
    addPoseReferences(m, all.table, all.azimuth_deg, m.info.training_views.label, 360.0 / m.info.pose_references.bins);
}

}  // namespace keyturn::learning
