// The plugin "plots": a report's plots drawn with Qt Charts (keyturn_ui), behind
// keyturn::ui::saveReportPlots (src/report_plots.cpp), so only a process that draws loads Qt.
#include <filesystem>

#include "keyturn/core/error.h"
#include "keyturn/core/plugin.h"
#include "keyturn/ui/confusion_plot.h"
#include "keyturn/ui/line_chart.h"
#include "keyturn/ui/report_plots.h"

namespace keyturn::ui {
namespace {

void drawReportPlots(const ReportPlots& plots, const std::string& dir) {
  namespace fs = std::filesystem;
  const auto pathOf = [&dir](const std::string& file) {
    const fs::path p = fs::path(dir) / file;
    std::error_code ec;
    if (!p.parent_path().empty() && !fs::is_directory(p.parent_path()) && !fs::create_directories(p.parent_path(), ec))
      throw Error(p.parent_path().string() + ": cannot create the folder (" + ec.message() + ")");
    return p.string();
  };
  for (const auto& c : plots.confusions) saveConfusionPng({c.title, c.labels, c.counts}, pathOf(c.file));
  for (const auto& c : plots.curves) {
    LineChart chart;
    chart.title = c.title;
    chart.x_label = c.x_label;
    chart.y_label = c.y_label;
    for (const auto& s : c.series) chart.series.push_back({s.name, s.x, s.y});
    chart.y_min = c.y_min;
    chart.y_max = c.y_max;
    chart.log_x = c.log_x;
    chart.log_y = c.log_y;
    chart.x_categories = c.x_categories;
    saveChartPng(chart, pathOf(c.file), c.width, c.height);
  }
}

}  // namespace
}  // namespace keyturn::ui

KEYTURN_PLUGIN_EXPORT bool keyturn_plots_save(const keyturn::ReportPlots& plots, const std::string& dir, std::string& error) {
  try {
    keyturn::ui::drawReportPlots(plots, dir);
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}
