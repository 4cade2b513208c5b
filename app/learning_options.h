#pragma once
// Command-line options of the learning tools: the classifiers' (evaluate and train) and
// --shard's I/N (describe and evaluate as array jobs).
#include <CLI/CLI.hpp>
#include <string>
#include <utility>

#include "keyturn/learning/classifier.h"
#include "keyturn/learning/open_set_calibration.h"

namespace keyturn::app {

void addClassifierOptions(CLI::App& cmd, learning::ClassifierParams& p);

// The open-set calibration's options (--false-accept, --open-set-groups); `method`, when given,
// adds train's --open-set auto|METHOD|none, put into the options by setOpenSetFlag.
void addOpenSetOptions(CLI::App& cmd, learning::OpenSetOptions& o, std::string* method = nullptr);
// auto: the default method when the data allows (o.required false); none: closed-set; else the
// method, checked (keyturn::Error naming --open-set).
void setOpenSetFlag(learning::OpenSetOptions& o, const std::string& method);
// "; open-set METHOD threshold T for R % false accepts (…)…" as train and recalibrate print it ("" closed-set).
std::string openSetSummary(const learning::OpenSet& open_set);

// --shard I/N (I counts from 1, as array jobs do) → {I - 1, N}; throws keyturn::Error naming
// --shard for text that is not I/N with 1 <= I <= N.
std::pair<int, int> parseShard(const std::string& text);

// Splits on spaces and commas: "kpd2 kpd2+kpa3,esf" → three sets.
std::vector<std::string> splitList(const std::string& list);

}  // namespace keyturn::app
