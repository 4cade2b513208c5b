#pragma once
// Training a model on a whole feature table (keyturn train) and applying one to
// new views (keyturn classify): the views described with the model's own
// parameters and only its blocks; features computed another way are refused.
#include <string>
#include <vector>

#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/model_file.h"
#include "keyturn/learning/protocols.h"

namespace keyturn::learning {

// A classifier of params.kind on the blocks of every row, labelled by kind, with its sidecar
// (the table's specification, the class names and means). fit_s: the training time.
Model trainModel(const FeatureTable& table, const std::vector<std::string>& blocks, LabelKind kind,
                 const ClassifierParams& params, double* fit_s = nullptr);

// The model's blocks of each view, described with the model's parameters (its spec; source names
// the model in errors); rows as describeViews makes them.
FeatureTable describeForModel(const Model& model, const std::vector<LabelledView>& views, int jobs,
                              DescribeProgress* progress, const std::string& source);

struct Classification {
  std::string view;
  int keypoints = 0;
  int best = 0;                       // index into the model's classes
  std::vector<double> probabilities;  // one per class
};

// Each usable row (described, or missing only some blocks) classified. Throws keyturn::Error
// naming source when the table's features were computed another way than the model's.
std::vector<Classification> classifyRows(const Model& model, const FeatureTable& table, const std::string& source);

}  // namespace keyturn::learning
