#pragma once
// A model's training views (training_views.h) as JSON: the "training_views" object of its sidecar.
#include <nlohmann/json.hpp>
#include <string>

#include "keyturn/learning/training_views.h"

namespace keyturn::learning {

// {"label", "open_set_groups", "open_set_seed", "captures": [[category, instance, elevation], …],
//  "views": [[capture, azimuth (null: none)], …] (a view with missing values: a third element,
//  their columns)}: each capture written once, a view naming it by index.
nlohmann::json trainingViewsJson(const TrainingViews& v);
// Throws keyturn::Error naming `source` for a malformed object, or when its views are not one per
// open-set reference (`references` of them) or name a column outside `inputs`.
TrainingViews parseTrainingViewsJson(const nlohmann::json& j, std::size_t references, int inputs,
                                     const std::string& source);

}  // namespace keyturn::learning
