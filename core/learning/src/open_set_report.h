#pragma once
// The open-set part of evaluate's report: per row of an open-set protocol, each method's AUROC,
// false-accept rate at the stated level and known-class accuracy against closed-set (JSON and a
// Markdown section), and the ROC curves (known vs unknown, all folds pooled) as report plots.
#include <nlohmann/json.hpp>
#include <string>

#include "keyturn/learning/evaluation_report.h"

namespace keyturn::learning {

// {"false_accept_stated", "methods": [{method, auroc_mean, auroc_sd, false_accept, …}]}; null for a
// row without open-set folds.
nlohmann::json openSetRowJson(const EvaluationRun& run, const EvaluationRow& row);
// "## Open-set answers" with its table; adds roc/*.png to plots. Empty without open-set rows.
std::string openSetMarkdown(const EvaluationRun& run, ReportPlots& plots);

}  // namespace keyturn::learning
