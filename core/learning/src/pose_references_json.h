#pragma once
// Pose fusion's references as JSON: the "pose_references" object of a model's sidecar
// (learning/view_fusion.h), so `keyturn classify --fuse pose` needs only the model.
#include <nlohmann/json.hpp>
#include <string>

#include "keyturn/learning/open_set.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

// {"bins", "sigma", "mean", "scale", "references": one [class, bin, values…] row per training view}.
// When `open_set` (a knn scorer of the same model) holds the same standardised rows, as `train`
// makes them, they are written once: {"bins", "sigma", "rows_of": "open_set", "reference_bins"}.
nlohmann::json poseReferencesJson(const PoseReferences& r, const OpenSet* open_set = nullptr);
// Throws keyturn::Error naming `source` for references that do not fit a model of `inputs`
// features and `classes` classes, or rows_of without a knn open set to take them from.
PoseReferences parsePoseReferencesJson(const nlohmann::json& j, int inputs, int classes, const std::string& source,
                                       const OpenSet* open_set = nullptr);

}  // namespace keyturn::learning
