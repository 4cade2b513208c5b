#pragma once
// A curve plot (core/report_plot_specs.h) drawn with Qt Charts into a PNG of its size, headless (the
// offscreen platform is chosen when there is no display).
#include <string>
#include <vector>

#include "keyturn/core/report_plot_specs.h"

namespace keyturn::plots {

// Throws keyturn::Error naming the file when it cannot be written.
void saveCurvePng(const CurvePlot& plot, const std::string& path);

// The text the plot shows, as laid out at its size (title, axis titles, tick labels, legend names);
// a label given too little room comes back elided ("..."). Nothing is written.
std::vector<std::string> curvePlotText(const CurvePlot& plot);

}  // namespace keyturn::plots
