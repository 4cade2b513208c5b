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
  std::vector<Prediction> out;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    if (t.rows[i].no_object) out.push_back({i, -1, {}, Answer::NoObject});
    else if (t.rows[i].keypoints >= 0 || t.rows[i].problem.empty()) usable.push_back(i);
  }
  if (!usable.empty()) {
    const Matrix x = t.select(model.info.blocks, usable);
    const Matrix p = model.classifier->predictProba(x);
    std::vector<std::string> cameras;
    for (std::size_t i : usable) cameras.push_back(t.rows[i].camera);
    const std::vector<double> scores =
        model.info.open_set.enabled() ? openSetScores(model.info.open_set, x, p, &cameras) : std::vector<double>();
    for (std::size_t k = 0; k < usable.size(); ++k) {
      const auto r = static_cast<Eigen::Index>(k);
      Prediction pr{usable[k], -1, std::vector<float>(p.row(r).data(), p.row(r).data() + p.cols())};
      if (p.cols() > 0) {
        Eigen::Index best = 0;
        p.row(r).maxCoeff(&best);
        pr.best = static_cast<int>(best);
      }
      if (!scores.empty()) pr.score = scores[k], pr.answer = model.info.open_set.answerFor(pr.score);
      out.push_back(std::move(pr));
    }
  }
  std::sort(out.begin(), out.end(), [](const Prediction& a, const Prediction& b) { return a.row < b.row; });
  return out;
}

std::string answerLabel(const ModelInfo& m, const Prediction& p) {
  if (p.answer != Answer::Class || p.best < 0) return answerName(p.answer == Answer::Class ? Answer::Unknown : p.answer);
  return m.classes.at(static_cast<std::size_t>(p.best));
}

Prediction predictionOf(const ModelInfo& m, const Matrix& x, const Matrix& p, const std::string& camera) {
  Prediction pr;
  if (p.rows() != 1) throw Error("one view's probabilities expected, got " + std::to_string(p.rows()) + " rows");
  pr.probabilities.assign(p.data(), p.data() + p.cols());
  Eigen::Index best = 0;
  if (p.cols() > 0) p.row(0).maxCoeff(&best), pr.best = static_cast<int>(best);
  if (m.open_set.enabled()) {
    const std::vector<std::string> cameras = {camera};
    pr.score = openSetScores(m.open_set, x, p, &cameras).at(0);
    pr.answer = m.open_set.answerFor(pr.score);
  }
  return pr;
}

}  // namespace keyturn::learning
