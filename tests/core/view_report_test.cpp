// describe's CSV row and --explain text for one view: as many columns as the
// header names, the counts in their columns, a file name with a comma quoted.
#include "keyturn/core/view_explanation.h"
#include "keyturn/core/view_report.h"

#include <gtest/gtest.h>

#include "keyturn/core/filter.h"
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
  EXPECT_EQ(e.rfind("cube.pcd: not filtered (--no-filter), " + std::to_string(d.input_points) + " valid points\n", 0), 0u) << e;
  EXPECT_NE(e.find("K = " + std::to_string(d.keypointCount()) + " keypoints\n"), std::string::npos) << e;
}
