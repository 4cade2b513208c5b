#pragma once
// A curve plot (core/report_plot_specs.h) drawn with Qt Charts into a PNG of its size, headless (the
// offscreen platform is chosen when there is no display).
#include <string>

#include "keyturn/core/report_plot_specs.h"

namespace keyturn::plots {

// Throws keyturn::Error naming the file when it cannot be written.
void saveCurvePng(const CurvePlot& plot, const std::string& path);

}  // namespace keyturn::plots
