#pragma once
// The plots a report links to (core/report_plot_specs.h) drawn as PNG files in
// the report's folder (sub-folders made as needed; dir "" for files named as they are).
// Drawn with Qt Charts in the plugin "plots", loaded on the first call.
#include <string>

#include "keyturn/core/report_plot_specs.h"

namespace keyturn::plots {

// Throws keyturn::Error naming the file that cannot be written.
void saveReportPlots(const ReportPlots& plots, const std::string& dir);

}  // namespace keyturn::plots
