#pragma once
// Line charts rendered to PNG with Qt Charts, headless (the offscreen platform
// is chosen when there is no display), for reports a person would rather see
// than read. The GUI shows the same charts live.
#include <cmath>
#include <string>
#include <vector>

namespace keyturn::ui {

struct Series {
  std::string name;
  std::vector<double> x, y;
};

struct LineChart {
  std::string title, x_label, y_label;
  std::vector<Series> series;
  double y_min = std::nan(""), y_max = std::nan("");  // NaN: from the data
  // Logarithmic axes (base 10, whole decades): points ≤ 0 on such an axis are left out.
  bool log_x = false, log_y = false;
  // Named x positions: x = 0, 1, … labelled with these (slanted) instead of numbers.
  std::vector<std::string> x_categories;
};

// Throws keyturn::Error naming the file when it cannot be written.
void saveChartPng(const LineChart& chart, const std::string& path, int width = 900, int height = 560);

}  // namespace keyturn::ui
