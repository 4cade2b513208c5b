#pragma once
// A trained model applied as `keyturn classify` applies it (and the Python
// module's Model.classify): views described with the model's own parameters and
// only its blocks; a table of features computed another way is refused.
#include <cmath>
#include <string>
#include <vector>

#include "keyturn/core/descriptor.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/model_file.h"

namespace keyturn::learning {

// The model's parameters (its sidecar's specification); `source` names the model in errors.
DescriptorOptions modelOptions(const Model& model, const std::string& source);
// An empty table of the model's blocks (each once) carrying its parameters' specification.
FeatureTable modelLayout(const Model& model, const std::string& source);
// The views described into the model's layout with its parameters (rows as describeViews makes them).
FeatureTable describeForModel(const Model& model, const std::vector<LabelledView>& views, int jobs,
                              DescribeProgress* progress, const std::string& source);

struct Prediction {
  std::size_t row = 0;               // index into the table's rows
  int best = -1;                     // the most probable class (-1 for no object)
  std::vector<float> probabilities;  // one per class, the model's order (empty for no object)
  Answer answer = Answer::Class;
  double score = std::nan("");       // the open-set score (NaN: closed-set model, or no object)
};

// The label a prediction answers: its class's name, "unknown" or "no object".
std::string answerLabel(const ModelInfo& model, const Prediction& p);
// The answer for one view's probabilities and features (x: one row, as the classifier saw it); camera:
// the view's (cameraOf, feature_cache.h; "" unknown), for a model whose open-set scale is per camera.
Prediction predictionOf(const ModelInfo& model, const Matrix& x, const Matrix& probabilities,
                        const std::string& camera = "");

// Predictions for the table's usable rows, in order: a row too empty to describe
// (FeatureRow::no_object) is answered "no object"; any other row that could not be described at
// all (keypoints -1 with a problem) is left out. With an open-set model a view scoring below its
// threshold is "unknown". Throws keyturn::Error when the table's specification differs from the
// model's.
std::vector<Prediction> predictRows(const Model& model, const FeatureTable& table, const std::string& source);

}  // namespace keyturn::learning
