#pragma once
// What a model keeps of its training views beyond their feature rows, so that it can be retrained
// with a new object added (model_enrollment.h): the open set's references are the training rows
// (standardised, one per view, in training order); this says, for each of them, what trainModel
// read from the table besides the features: the view's category, instance and elevation (the
// category left out by the open-set calibration, the capture group its turns are read in), its
// camera (the open-set camera scale), its turntable angle and which of its values were missing; and how the model was labelled and
// calibrated.
#include <cstdint>
#include <string>
#include <vector>

#include "keyturn/learning/protocols.h"

namespace keyturn::learning {

struct TrainingView {
  std::string cls, instance, elevation;
  double azimuth_deg = 0;     // NaN: none
  std::vector<int> missing;   // columns the view lacked (NaN in training; the reference holds the mean)
  std::string camera;         // the view's camera (cameraOf: its organized grid), "" unknown: the open-set camera scale
};

struct TrainingViews {
  LabelKind label = LabelKind::Instance;  // the model's classes: instances or categories
  int open_set_groups = 5;                // OpenSetOptions::groups the threshold was calibrated with
  std::uint64_t open_set_seed = 7;        // OpenSetOptions::seed (the categories' shuffle into groups)
  std::vector<TrainingView> views;        // one per open-set reference, in the same order
  bool empty() const { return views.empty(); }
};

}  // namespace keyturn::learning
