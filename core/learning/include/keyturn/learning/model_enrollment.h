#pragma once
// Adding an object to a trained model (keyturn enroll): the model's own training rows (its open
// set's references with their training views, training_views.h) and the new object's views,
// described with the model's parameters, retrained as keyturn train made the model: the same
// blocks, label kind and classifier parameters, the open set re-calibrated by the same method,
// false-accept rate and groups, and pose references refitted when the model has them.
#include <string>
#include <vector>

#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/model_file.h"

namespace keyturn::learning {

// The model's training views as a table in its layout (modelLayout) and their turntable angles
// (NaN: none). Values come back from the standardised references (4 decimals of a spread: the
// distances move by < 1e-4), a 0 as 0; a value the view lacked is NaN again. enrollObject rounds the
// new object's values the same way, so that nothing but their features tells old views from new. Throws keyturn::Error naming
// `source` when the model keeps no training views (trained before they were stored, or closed-set).
struct TrainingTable {
  FeatureTable table;
  std::vector<double> azimuth_deg;
};
TrainingTable modelTrainingTable(const Model& model, const std::string& source);

// The class the model would give an object of category `cls` and instance `instance` (its label
// kind). Throws keyturn::Error naming `source` when the model keeps no training views or already
// has that class (or that instance).
std::string enrolledClass(const Model& model, const std::string& cls, const std::string& instance,
                          const std::string& source);

struct Enrollment {
  Model model;
  std::size_t training_views = 0;  // the model's own
  std::size_t new_views = 0;       // the object's, described
  std::size_t skipped = 0;         // the object's views that could not be described (left out)
  double fit_s = 0;                // the final classifier's training
};

// The model retrained on its training views and `views`: one object's (one category and instance,
// not yet in the model), rows in the model's layout (describeForModel) with their angles (one per
// row; NaN: none). Views that could not be described are left out. Throws keyturn::Error for views
// of several objects or none described, features computed another way than the model's, or a model
// without training views.
Enrollment enrollObject(const Model& model, const FeatureTable& views, const std::vector<double>& azimuth_deg,
                        const std::string& source);

}  // namespace keyturn::learning
