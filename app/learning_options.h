#pragma once
// Command-line options of the classifiers, shared by evaluate and train.
#include <CLI/CLI.hpp>

#include "keyturn/learning/classifier.h"

namespace keyturn::app {

void addClassifierOptions(CLI::App& cmd, learning::ClassifierParams& p);

// Splits on spaces and commas: "kpd2 kpd2+kpa3,esf" → three sets.
std::vector<std::string> splitList(const std::string& list);

}  // namespace keyturn::app
