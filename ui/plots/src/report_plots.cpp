#include "keyturn/plots/report_plots.h"

#include "keyturn/core/error.h"
#include "keyturn/core/plugin.h"

namespace keyturn::plots {

// Qt (Widgets, Charts) is loaded with the plugin "plots" (plugin/report_plots_qt.cpp) when a
// report is drawn, not at every start of the tool.
void saveReportPlots(const ReportPlots& plots, const std::string& dir) {
  using Save = bool(const ReportPlots&, const std::string&, std::string&);
  static auto* save = pluginFunction<Save>("plots", "keyturn_plots_save");
  std::string error;
  if (!save(plots, dir, error)) throw Error(error);
}

std::vector<std::string> drawnText(const CurvePlot& plot) {
  using Text = bool(const CurvePlot&, std::vector<std::string>&, std::string&);
  static auto* text_of = pluginFunction<Text>("plots", "keyturn_plots_text");
  std::vector<std::string> text;
  std::string error;
  if (!text_of(plot, text, error)) throw Error(error);
  return text;
}

}  // namespace keyturn::plots
