#pragma once
// An open-set scorer and its threshold as JSON: the "open_set" object of a model's sidecar.
#include <nlohmann/json.hpp>
#include <string>

#include "keyturn/learning/open_set.h"

namespace keyturn::learning {

// {"method", "threshold", "false_accept", "calibration": {...}} and, for knn, "neighbours",
// "mean", "scale" and "references": one [class, values…] row per training view.
nlohmann::json openSetJson(const OpenSet& s);
// Throws keyturn::Error naming `source` for an unknown method or a scorer that does not fit a
// model of `inputs` features and `classes` classes.
OpenSet parseOpenSetJson(const nlohmann::json& j, int inputs, int classes, const std::string& source);

}  // namespace keyturn::learning
