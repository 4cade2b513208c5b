// Report plots drawn headless (no window, no display): each file a PNG of the
// size asked for, sub-folders made, an unwritable file named.
#include "keyturn/plots/report_plots.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "keyturn/core/error.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

// Width and height from a PNG's IHDR chunk; {0, 0} when the file is no PNG.
std::pair<unsigned, unsigned> pngSize(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (b.size() < 24 || b.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || b.compare(12, 4, "IHDR") != 0) return {0, 0};
  auto be = [&](std::size_t at) {
    unsigned v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
    return v;
  };
  return {be(16), be(20)};
}

bool elided(const std::string& t) { return t.find("...") != std::string::npos || t.find("\u2026") != std::string::npos; }

CurvePlot pdfPlot(int width, int height) {
  CurvePlot c;
  c.title = "kpd2 of a";
  c.x_label = "bin";
  c.y_label = "probability";
  c.series = {{"mean", {0, 1, 2, 3}, {0.7, 0.1, 0.1, 0.1}}};
  c.width = width;
  c.height = height;
  return c;
}

}  // namespace

// What the plot shows, not only its size (issue 51: labels elided to "…" were once found by eye).
// Qt Charts' value axes carry 5 ticks by default: 0 to 3 in steps of 0.75, 0.1 to 0.7 in steps of
// 0.15, printed with %.3g.
TEST(ReportPlots, APlotShowsItsTitleAxesTicksAndLegendUncut) {
  const std::vector<std::string> text = plots::drawnText(pdfPlot(640, 400));
  for (const char* want : {"kpd2 of a", "bin", "probability", "mean", "0", "0.75", "1.5", "2.25", "3", "0.1", "0.25",
                           "0.4", "0.55", "0.7"})
    EXPECT_NE(std::find(text.begin(), text.end(), want), text.end()) << want;
  for (const auto& t : text) EXPECT_FALSE(elided(t)) << t;
}

// The check above can fail: the same plot at 150 × 90 has no room for its labels, and they come back cut.
TEST(ReportPlots, APlotTooSmallForItsLabelsShowsThemCut) {
  CurvePlot c = pdfPlot(150, 90);
  c.title = "kpd2 of a view with a long name";
  const std::vector<std::string> text = plots::drawnText(c);
  EXPECT_TRUE(std::any_of(text.begin(), text.end(), elided));
}

TEST(ReportPlots, EachPlotIsAPngOfItsSizeInItsSubFolder) {
  const keyturn::test::ScratchFolder scratch("ui_plots");
  const std::filesystem::path& dir = scratch.path;
  ReportPlots plots;
  CurvePlot curve;
  curve.file = "pdfs/a.png";
  curve.title = "kpd2 of a";
  curve.series = {{"mean", {0, 1, 2, 3}, {0.7, 0.1, 0.1, 0.1}}};
  curve.width = 640;
  curve.height = 400;
  plots.curves.push_back(curve);
  CurvePlot log = curve;
  log.file = "scaling.png";
  log.width = 900;
  log.height = 560;
  log.log_x = log.log_y = true;
  log.series = {{"time", {1000, 10000, 100000}, {1, 8, 90}}};
  plots.curves.push_back(log);
  plots.confusions.push_back({"confusion/kfold.png", "kfold", {"a", "b"}, {{12, 0}, {1, 11}}});
  plots::saveReportPlots(plots, dir.string());
  EXPECT_EQ(pngSize(dir / "pdfs/a.png"), (std::pair<unsigned, unsigned>{640, 400}));
  EXPECT_EQ(pngSize(dir / "scaling.png"), (std::pair<unsigned, unsigned>{900, 560}));
  const auto confusion = pngSize(dir / "confusion/kfold.png");
  EXPECT_GT(confusion.first, 0u);
  EXPECT_GT(confusion.second, 0u);
  fs::remove_all(dir);
}

TEST(ReportPlots, AFileThatCannotBeWrittenIsNamed) {
  ReportPlots plots;
  CurvePlot c;
  c.file = "/proc/keyturn-no/such.png";
  c.series = {{"s", {0, 1}, {0, 1}}};
  plots.curves.push_back(c);
  const std::string msg = test::errorOf([&] { plots::saveReportPlots(plots, ""); });
  EXPECT_EQ(msg.rfind("/proc/keyturn-no: cannot create the folder (", 0), 0u) << msg;
}
