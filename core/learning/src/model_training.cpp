#include "keyturn/learning/model_training.h"

#include <chrono>
#include <set>

namespace keyturn::learning {

Model trainModel(const FeatureTable& t, const std::vector<std::string>& blocks, LabelKind kind,
                 const ClassifierParams& params, double* fit_s, const std::optional<OpenSetOptions>& open_set) {
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
    OpenSetOptions o = *open_set;
    o.methods.resize(1);
    std::vector<std::string> categories;
    for (const auto& row : t.rows) categories.push_back(row.cls);
    const std::set<std::string> distinct(categories.begin(), categories.end());
    if (o.required || distinct.size() >= kOpenSetMinCategories)
      m.info.open_set = calibrateOpenSets(x, y, categories, params, o).front();
  }
  return m;
}

}  // namespace keyturn::learning
