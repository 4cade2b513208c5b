#pragma once
// Training a model on a whole feature table (keyturn train); applying one is
// model_predictions.h.
#include <string>
#include <vector>

#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/model_file.h"
#include "keyturn/learning/protocols.h"

namespace keyturn::learning {

// A classifier of params.kind on the blocks of every row, labelled by kind, with its sidecar
// (the table's specification, the class names and means). fit_s: the training time.
Model trainModel(const FeatureTable& table, const std::vector<std::string>& blocks, LabelKind kind,
                 const ClassifierParams& params, double* fit_s = nullptr);

}  // namespace keyturn::learning
