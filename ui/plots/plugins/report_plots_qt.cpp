// The plugin "plots": a report's plots drawn with Qt Charts, behind keyturn::plots::saveReportPlots
// (src/report_plots.cpp), so only a process that draws loads Qt.
#include <filesystem>

#include "confusion_plot_png.h"
#include "curve_plot_png.h"
#include "keyturn/core/error.h"
#include "keyturn/core/plugin.h"
#include "keyturn/core/report_plot_specs.h"

namespace keyturn::plots {
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
  for (const auto& c : plots.confusions) saveConfusionPng(c, pathOf(c.file));
  for (const auto& c : plots.curves) saveCurvePng(c, pathOf(c.file));
}

}  // namespace
}  // namespace keyturn::plots

KEYTURN_PLUGIN_EXPORT bool keyturn_plots_save(const keyturn::ReportPlots& plots, const std::string& dir, std::string& error) {
  try {
    keyturn::plots::drawReportPlots(plots, dir);
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

KEYTURN_PLUGIN_EXPORT bool keyturn_plots_text(const keyturn::CurvePlot& plot, std::vector<std::string>& text,
                                              std::string& error) {
  try {
    text = keyturn::plots::curvePlotText(plot);
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}
