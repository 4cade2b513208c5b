#include "keyturn/learning/model_training.h"

#include <algorithm>
#include <chrono>

#include "keyturn/core/error.h"
#include "keyturn/learning/feature_spec.h"

namespace keyturn::learning {

Model trainModel(const FeatureTable& t, const std::vector<std::string>& blocks, LabelKind kind,
                 const ClassifierParams& params, double* fit_s) {
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
  return m;
}

FeatureTable describeForModel(const Model& m, const std::vector<LabelledView>& views, int jobs,
                              DescribeProgress* progress, const std::string& source) {
  const DescriptorOptions options = descriptorOptionsFromSpec(m.info.spec, source);
  std::vector<std::string> blocks;
  for (const auto& b : m.info.blocks)
    if (std::find(blocks.begin(), blocks.end(), b) == blocks.end()) blocks.push_back(b);
  FeatureTable t = featureLayout(blocks, options);
  t.rows = describeViews(views, options, t, jobs, progress);
  return t;
}

std::vector<Classification> classifyRows(const Model& m, const FeatureTable& t, const std::string& source) {
  const auto diff = specDifferences(m.info.spec, t.spec);
  if (!diff.empty()) {
    std::string msg = source + ": the model was trained on features computed another way (";
    for (std::size_t i = 0; i < diff.size(); ++i) msg += (i ? "; " : "") + diff[i];
    throw Error(msg + "): describe the views with the model's parameters");
  }
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    if (t.rows[i].keypoints >= 0 || t.rows[i].problem.empty()) usable.push_back(i);
  std::vector<Classification> out;
  if (usable.empty()) return out;
  const Matrix p = m.classifier->predictProba(t.select(m.info.blocks, usable));
  for (std::size_t k = 0; k < usable.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    Classification c;
    c.view = t.rows[usable[k]].id;
    c.keypoints = t.rows[usable[k]].keypoints;
    Eigen::Index best = 0;
    p.row(row).maxCoeff(&best);
    c.best = static_cast<int>(best);
    for (Eigen::Index j = 0; j < p.cols(); ++j) c.probabilities.push_back(p(row, j));
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace keyturn::learning
