// describe's CSV row and --explain text for one view: as many columns as the
// header names, the counts in their columns, a file name with a comma quoted;
// and many files described at once.
#include "keyturn/core/view_explanation.h"
#include "keyturn/core/view_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/describe_files.h"
#include "keyturn/core/filter.h"
#include "support/scratch_path.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

namespace {

std::vector<std::string> csvCells(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
      else quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

ViewDescriptor cube(const DescriptorOptions& o) {
  return describeView(test::unorganized(test::cubeSurface(0.1f, 21, Eigen::Vector3f(0, 0, 1))), o);
}

}  // namespace

TEST(ViewReport, RowHasTheHeadersColumnsAndTheViewsCounts) {
  DescriptorOptions o;
  o.filter = false;
  o.features = {Feature::KPD2, Feature::GKPD2};
  o.histogram.bins = 8;
  const ViewDescriptor d = cube(o);
  const auto header = csvCells(describeCsvHeader(o.features, 8));
  const auto row = csvCells(describeCsvRow("a,\"b\".pcd", d));
  ASSERT_EQ(row.size(), header.size());
  EXPECT_EQ(header.size(), 17u + 2 * 8);
  EXPECT_EQ(header[17], "kpd2_0");
  EXPECT_EQ(header.back(), "gkpd2_7");
  EXPECT_EQ(row[0], "a,\"b\".pcd");  // quoted, and read back whole
  EXPECT_EQ(row[1], std::to_string(d.points));
  EXPECT_EQ(row[2], std::to_string(d.keypointCount()));
  EXPECT_EQ(row[7], "unfiltered");
  double sum = 0;
  for (std::size_t c = 17; c < 17 + 8; ++c) sum += std::stod(row[c]);
  EXPECT_NEAR(sum, 1.0, 1e-4);  // a PDF
}

TEST(ViewReport, ExplanationNamesTheInputAndTheResult) {
  DescriptorOptions o;
  o.filter = false;
  const ViewDescriptor d = cube(o);
  const std::string e = explainView("cube.pcd", d);
  EXPECT_EQ(e.rfind("cube.pcd: not filtered (the filter is off), " + std::to_string(d.input_points) + " valid points\n", 0), 0u) << e;
  EXPECT_NE(e.find("K = " + std::to_string(d.keypointCount()) + " keypoints\n"), std::string::npos) << e;
}

// Many files: a corrupt one is reported by name and skipped, the good one's row kept, in file order.
TEST(ViewReport, ManyFilesKeepTheGoodRowsAndNameTheBadFile) {
  const test::ScratchFolder scratch("describe_files");
  const auto& dir = scratch.made();
  const std::string good = (dir / "cube.pcd").string(), bad = (dir / "broken.pcd").string();
  saveCloud(good, test::unorganized(test::cubeSurface(0.1f, 21, Eigen::Vector3f(0, 0, 1))));
  std::ofstream(bad) << "# .PCD v0.7\nFIELDS x y\nnot a cloud\n";

  DescribeFilesOptions o;
  o.descriptor.filter = false;
  o.descriptor.features = {Feature::KPD2};
  o.descriptor.histogram.bins = 4;
  o.descriptor.low_keypoints = 100000;  // every view is "thin": its warning must appear
  o.prefix = "tool: ";
  int calls = 0;
  std::mutex m;
  const DescribedFiles d = describeFiles({bad, good}, o, [&] { std::lock_guard<std::mutex> l(m); ++calls; });

  EXPECT_EQ(calls, 2);
  EXPECT_EQ(d.described, 1u);
  EXPECT_EQ(d.failed, 1u);
  EXPECT_EQ(d.flagged, 1u);
  std::istringstream csv(d.csv);
  std::string header, row, extra;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_FALSE(std::getline(csv, extra));
  EXPECT_EQ(csvCells(row)[0], good);
  ASSERT_EQ(d.messages.size(), 2u);
  EXPECT_EQ(d.messages[0].rfind("tool: " + bad + ": ", 0), 0u) << d.messages[0];  // named once, first
  EXPECT_NE(d.messages[1].find("only "), std::string::npos) << d.messages[1];
  EXPECT_NE(d.messages[1].find(good), std::string::npos);
}
