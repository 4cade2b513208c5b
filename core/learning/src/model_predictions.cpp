#include "keyturn/learning/model_predictions.h"

#include <algorithm>

#include "keyturn/core/descriptor_parameters.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/feature_spec.h"

namespace keyturn::learning {

DescriptorOptions modelOptions(const Model& model, const std::string& source) {
  return descriptorOptionsFromSpec(model.info.spec, source + "/model.json");
}

FeatureTable modelLayout(const Model& model, const std::string& source) {
  std::vector<std::string> blocks;
  for (const auto& b : model.info.blocks)
    if (std::find(blocks.begin(), blocks.end(), b) == blocks.end()) blocks.push_back(b);
  return featureLayout(blocks, modelOptions(model, source));
}

FeatureTable describeForModel(const Model& model, const std::vector<LabelledView>& views, int jobs,
                              DescribeProgress* progress, const std::string& source) {
  FeatureTable t = modelLayout(model, source);
  t.rows = describeViews(views, modelOptions(model, source), t, jobs, progress);
  return t;
}

std::vector<Prediction> predictRows(const Model& model, const FeatureTable& t, const std::string& source) {
  // A model or table written before a parameter existed was made the way its absence means.
  const auto diff = specDifferences(completedParameterSpec(model.info.spec), completedParameterSpec(t.spec));
  if (!diff.empty()) {
    std::string msg = source + ": the model was trained on features computed another way (";
    for (std::size_t i = 0; i < diff.size(); ++i) msg += (i ? "; " : "") + diff[i];
    throw Error(msg + "): describe the views with the model's parameters");
  }
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < t.rows.size(); ++i)
    if (t.rows[i].keypoints >= 0 || t.rows[i].problem.empty()) usable.push_back(i);
  std::vector<Prediction> out;
  if (usable.empty()) return out;
  const Matrix p = model.classifier->predictProba(t.select(model.info.blocks, usable));
  for (std::size_t k = 0; k < usable.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    Eigen::Index best = 0;
    p.row(r).maxCoeff(&best);
    out.push_back({usable[k], static_cast<int>(best), std::vector<float>(p.row(r).data(), p.row(r).data() + p.cols())});
  }
  return out;
}

}  // namespace keyturn::learning
