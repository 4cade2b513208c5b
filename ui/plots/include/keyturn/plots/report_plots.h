#pragma once
// The plots a report links to (core/report_plot_specs.h) drawn as PNG files in
// the report's folder (sub-folders made as needed; dir "" for files named as they are).
// Drawn with Qt Charts in the plugin "plots", loaded on the first call.
#include <string>
#include <vector>

#include "keyturn/core/report_plot_specs.h"

namespace keyturn::plots {

// Throws keyturn::Error naming the file that cannot be written.
void saveReportPlots(const ReportPlots& plots, const std::string& dir);

// The text a curve plot shows, as Qt Charts laid it out at the plot's size: title, axis titles,
// tick labels and legend names. A label given too little room comes back elided ("..." or "…"), so
// a caller (the tests) can tell a readable plot from one whose labels were cut.
std::vector<std::string> drawnText(const CurvePlot& plot);

}  // namespace keyturn::plots
