#pragma once
// The plots a report links to, as data: what to draw and the file to draw it in
// (relative to the report's folder). The libraries decide the plots (evaluate's,
// consistency's, bench --scaling's); ui/plots/report_plots.h draws them (PNG, Qt), so
// core and learning stay free of Qt.
#include <cmath>
#include <string>
#include <vector>

namespace keyturn {

struct CurveSeries {
  std::string name;
  std::vector<double> x, y;
  // Pairs of series (a detector natively and at a budget) share a colour, one dashed: colour is an
  // index into the plotter's palette, -1 = by the series' place (past the palette: dashed).
  int colour = -1;
  bool dashed = false;
};

struct CurvePlot {
  std::string file;
  std::string title, x_label, y_label;
  std::vector<CurveSeries> series;
  double y_min = std::nan(""), y_max = std::nan("");  // NaN: from the data
  bool log_x = false, log_y = false;  // base 10; points ≤ 0 on such an axis are left out
  // Named x positions: x = 0, 1, … are drawn as these labels (a category axis) instead of numbers.
  std::vector<std::string> x_categories;
  int width = 900, height = 560;
};

struct ConfusionPlot {
  std::string file, title;
  std::vector<std::string> labels;
  std::vector<std::vector<int>> counts;  // [true][predicted]
};

struct ReportPlots {
  std::vector<CurvePlot> curves;
  std::vector<ConfusionPlot> confusions;
};

// A name safe in a file name: everything but letters, digits, '-' and '_' becomes '_'.
std::string fileSafeName(std::string name);

}  // namespace keyturn
