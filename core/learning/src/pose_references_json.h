#pragma once
// Pose fusion's references as JSON: the "pose_references" object of a model's sidecar
// (learning/view_fusion.h), so `keyturn classify --fuse pose` needs only the model.
#include <nlohmann/json.hpp>
#include <string>

#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

// {"bins", "sigma", "mean", "scale", "references": one [class, bin, values…] row per training view}.
nlohmann::json poseReferencesJson(const PoseReferences& r);
// Throws keyturn::Error naming `source` for references that do not fit a model of `inputs`
// features and `classes` classes.
PoseReferences parsePoseReferencesJson(const nlohmann::json& j, int inputs, int classes, const std::string& source);

}  // namespace keyturn::learning
