#pragma once
// Gradient boosting through XGBoost's C API, objective multi:softprob.
#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

std::unique_ptr<Classifier> makeXgboostClassifier(const ClassifierParams& params);

}  // namespace keyturn::learning
