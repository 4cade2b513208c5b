#pragma once
// A report as evaluate writes each of its kinds: report.csv, report.json, the plots, then report.md
// (last, after the plots it links to). Report: any struct with csv, json, markdown and plots.
#include <filesystem>
#include <string>

#include "keyturn/core/durable_file.h"
#include "keyturn/plots/report_plots.h"

namespace keyturn::app {

template <typename Report>
void writeReportFiles(const std::string& dir, const Report& report) {
  const std::filesystem::path out(dir);
  std::filesystem::create_directories(out);
  writeFileDurably((out / "report.csv").string(), report.csv);
  writeFileDurably((out / "report.json").string(), report.json);
  plots::saveReportPlots(report.plots, dir);
  writeFileDurably((out / "report.md").string(), report.markdown);
}

}  // namespace keyturn::app
