#pragma once
// A small fully connected network in libtorch: inputs (standardised with the
// training set's mean and spread) → hidden ReLU layers with dropout → classes.
#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

// Made by the plugin "mlp" (this file's .cpp with libtorch, built as a module).
std::unique_ptr<Classifier> makeMlpClassifier(const ClassifierParams& params);
using MakeMlpClassifierFunction = Classifier*(const ClassifierParams& params);

}  // namespace keyturn::learning
