#pragma once
// A trained model on disk: a folder MODEL/ with model.json (the sidecar: which
// classifier, its parameters, the class names and the feature specification)
// and the classifier's own file (model.xgb.json for XGBoost, model.pt for the
// libtorch network). Features computed another way are refused. The sidecar's
// optional "open_set" holds the open-set method and threshold (open_set.h).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"
#include "keyturn/learning/open_set.h"
#include "keyturn/learning/training_views.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

struct ModelInfo {
  ClassifierParams params;
  std::vector<std::string> classes;
  std::vector<std::string> blocks;            // feature blocks, concatenated in this order
  int inputs = 0;
  std::map<std::string, std::string> spec;    // every parameter that shapes the features
  // Optional: each class's mean training feature vector (classes × inputs), so a
  // view's PDFs can be shown over those of the class it was taken for.
  std::vector<std::vector<float>> class_means;
  // Optional: the open-set score and threshold (open_set.h). A model without one (every model
  // written before issue 34) is closed-set: each view gets a class.
  OpenSet open_set;
  // Optional: the training views by azimuth for pose fusion (view_fusion.h; "pose_references" in
  // the sidecar). A model without them fuses views independently.
  PoseReferences pose_references;
  // Optional: what retraining needs beside the open set's references, which are the training rows
  // (enrollment: model_enrollment.h; "training_views" in the sidecar). A model without it cannot
  // take a new object: it is retrained with keyturn train.
  TrainingViews training_views;
};

// The per-class mean of each column, ignoring NaN (a block a view lacks); 0 where a
// class has no value at all. y holds class indices.
std::vector<std::vector<float>> classMeans(const Matrix& x, const std::vector<int>& y, int classes);

struct Model {
  ModelInfo info;
  std::unique_ptr<Classifier> classifier;
};

// Writes MODEL/ atomically (a temporary folder renamed into place).
void saveModel(const std::string& dir, const Model& model);
// Throws keyturn::Error naming the file for a missing, corrupt or inconsistent model.
Model loadModel(const std::string& dir);
// Parses a sidecar's text (exposed for the fuzzer); `source` names it in errors.
ModelInfo parseModelSidecar(const std::string& text, const std::string& source);

// "bins: model 32, features 64" for each key that differs; empty when they agree.
std::vector<std::string> specDifferences(const std::map<std::string, std::string>& model,
                                         const std::map<std::string, std::string>& features);

}  // namespace keyturn::learning
