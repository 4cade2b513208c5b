#include "keyturn/learning/model_training.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "keyturn/core/error.h"
#include "fold_views.h"

namespace keyturn::learning {

OpenSet calibrateModelOpenSet(const FeatureTable& t, const Matrix& x, const std::vector<int>& y,
                              const std::vector<std::string>& blocks, const ClassifierParams& params,
                              const OpenSetOptions& options, const std::vector<double>& azimuth_deg) {
  OpenSetOptions o = options;
  o.methods.resize(1);
  checkOpenSetDistanceFor(o.distance, blocks);
  checkOpenSetMethodsFor(o.methods, blocks);
  std::vector<std::string> categories;
  for (const auto& row : t.rows) categories.push_back(row.cls);
  // Turns need every view's angle (a view without one would leave holes the turns skip silently).
  const bool posed = !azimuth_deg.empty() && std::all_of(azimuth_deg.begin(), azimuth_deg.end(),
                                                         [](double a) { return std::isfinite(a); });
  TurnRows turns;
  if (posed) {
    turns.azimuth_deg = azimuth_deg;
    for (const auto& row : t.rows) turns.group.push_back(detail::captureGroupOf(row));
  }
  std::vector<std::string> cameras, instances;  // each view's camera ("" : none known) and instance
  for (const auto& row : t.rows) cameras.push_back(row.camera), instances.push_back(row.instance);
  return calibrateOpenSets(x, y, categories, params, o, posed ? &turns : nullptr, &cameras, &instances).front();
}

Model trainModel(const FeatureTable& t, const std::vector<std::string>& blocks, LabelKind kind,
                 const ClassifierParams& params, double* fit_s, const std::optional<OpenSetOptions>& open_set,
                 const std::vector<double>& azimuth_deg) {
  if (!azimuth_deg.empty() && azimuth_deg.size() != t.rows.size())
    throw Error("training: " + std::to_string(t.rows.size()) + " views but " + std::to_string(azimuth_deg.size()) + " angles");
  const Labels labels = labelRows(t, kind);
  Model m;
  m.info.params = params;
  m.info.blocks = blocks;
  m.info.spec = t.spec;
  m.info.classes = labels.names;
  const std::vector<int>& y = labels.of_row;
  std::vector<std::size_t> all(t.rows.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const Matrix x = t.select(m.info.blocks, all);
  m.info.inputs = static_cast<int>(x.cols());
  m.info.class_means = classMeans(x, y, static_cast<int>(m.info.classes.size()));
  m.classifier = makeClassifier(m.info.params);
  const auto t0 = std::chrono::steady_clock::now();
  m.classifier->fit(x, y, static_cast<int>(m.info.classes.size()));
  if (fit_s) *fit_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (open_set && !open_set->methods.empty()) {
    const OpenSetOptions& o = *open_set;
    std::set<std::string> distinct;
    for (const auto& row : t.rows) distinct.insert(row.cls);
    if (o.required || distinct.size() >= kOpenSetMinCategories)
      m.info.open_set = calibrateModelOpenSet(t, x, y, blocks, params, o, azimuth_deg);
    // The references are the training rows: with what else each row was trained by, the model can
    // be retrained with an object added (model_enrollment.h).
    if (keepsReferences(m.info.open_set.method)) {
      TrainingViews& v = m.info.training_views;
      v.label = kind, v.open_set_groups = o.groups, v.open_set_seed = o.seed;
      for (std::size_t r = 0; r < t.rows.size(); ++r) {
        TrainingView view{t.rows[r].cls, t.rows[r].instance, t.rows[r].elevation,
                          azimuth_deg.empty() ? std::nan("") : azimuth_deg[r], {}, t.rows[r].camera};
        for (Eigen::Index k = 0; k < x.cols(); ++k)
          if (!std::isfinite(x(static_cast<Eigen::Index>(r), k))) view.missing.push_back(static_cast<int>(k));
        v.views.push_back(std::move(view));
      }
    }
  }
  return m;
}

}  // namespace keyturn::learning
