#pragma once
// A small fully connected network in libtorch: inputs (standardised with the
// training set's mean and spread) → hidden ReLU layers with dropout → classes.
#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

std::unique_ptr<Classifier> makeMlpClassifier(const ClassifierParams& params);

}  // namespace keyturn::learning
