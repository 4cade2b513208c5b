#pragma once
// A confusion matrix (core/report_plot_specs.h) as a PNG heat map (rows: true class, columns:
// predicted), each cell shaded by the share of its row and labelled with its count.
#include <string>

#include "keyturn/core/report_plot_specs.h"

namespace keyturn::plots {

// Throws keyturn::Error naming the file when it cannot be written.
void saveConfusionPng(const ConfusionPlot& plot, const std::string& path);

}  // namespace keyturn::plots
