#pragma once
// A trained model applied as `keyturn classify` applies it (and the Python
// module's Model.classify): views described with the model's own parameters and
// only its blocks; a table of features computed another way is refused.
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
  int best = -1;                     // class index
  std::vector<float> probabilities;  // one per class, the model's order
};

// Predictions for the table's usable rows, in order (a row that could not be described at all,
// keypoints -1 with a problem, is left out). Throws keyturn::Error when the table's
// specification differs from the model's.
std::vector<Prediction> predictRows(const Model& model, const FeatureTable& table, const std::string& source);

}  // namespace keyturn::learning
