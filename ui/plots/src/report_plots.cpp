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

}  // namespace keyturn::plots
