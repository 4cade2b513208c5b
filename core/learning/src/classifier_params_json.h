#pragma once
// The classifier parameters as JSON, one writer for the model sidecar and
// evaluate's parts (which must agree on every parameter that shapes a model).
#include <nlohmann/json.hpp>

#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

// {"classifier", "seed", "xgboost": {...}, "mlp": {...}}; threads are left out (no effect on the model).
nlohmann::json classifierParamsJson(const ClassifierParams& p);

}  // namespace keyturn::learning
