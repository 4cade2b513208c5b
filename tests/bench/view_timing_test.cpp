// One view timed through the chain and PCL's baselines: the figures hang together
// and the table prints them.
#include "keyturn/bench/view_timing.h"

#include <gtest/gtest.h>

#include "keyturn/core/error.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

namespace {

Cloud cube() { return test::unorganized(test::cubeSurface(0.1f, 21, Eigen::Vector3f(0, 0, 1))); }

DescriptorOptions unfiltered() {
  DescriptorOptions o;
  o.filter = false;
  return o;
}

}  // namespace

TEST(BenchView, StagesSpreadAndCountsMatchTheDescriptor) {
  bench::BenchRuns runs;
  runs.repetitions = 3;
  runs.pcl_repetitions = 2;
  std::vector<int> calls;
  runs.progress = [&](const std::string& label, int done, int total) {
    EXPECT_EQ(label, "bench cube");
    EXPECT_EQ(total, 3);
    calls.push_back(done);
  };
  const Cloud c = cube();
  const nlohmann::json j = bench::benchView("cube", c, runs, unfiltered());
  EXPECT_EQ(calls, (std::vector<int>{0, 1, 2, 3}));
  // The bench times describe's own chain: its counts are describe's (both from the library), and
  // they are a cube's: 21³ − 19³ = 2402 surface points by hand, some keypoints at least at its 8
  // corners (where, descriptor_test.cpp checks), no more points kept than given.
  const ViewDescriptor d = describeView(c, unfiltered());
  EXPECT_EQ(j["keypoints"].get<int>(), d.keypointCount());
  EXPECT_EQ(j["points"].get<std::size_t>(), d.points);
  EXPECT_EQ(j["frame_pixels"].get<std::size_t>(), 2402u);
  EXPECT_GE(j["keypoints"].get<int>(), 8);
  EXPECT_GT(j["points"].get<std::size_t>(), 0u);
  EXPECT_LE(j["points"].get<std::size_t>(), 2402u);
  EXPECT_EQ(j["repetitions"].get<int>(), 3);
  for (const char* stage : {"filter", "iss", "kpd", "graph", "gkpd", "total", "pcl_iss", "pcl_esf", "pcl_vfh"}) {
    const auto& s = j["stages"][stage];
    EXPECT_LE(s["min_ms"].get<double>(), s["median_ms"].get<double>()) << stage;
    EXPECT_LE(s["median_ms"].get<double>(), s["max_ms"].get<double>()) << stage;
  }
  EXPECT_GT(j["total_ms"].get<double>(), 0.0);
  EXPECT_GE(j["total_ms"].get<double>(), j["iss_ms"].get<double>());
  const double ratio = j["iss_speedup_vs_pcl"].get<double>();
  EXPECT_NEAR(ratio, j["pcl_iss_ms"].get<double>() / j["iss_ms"].get<double>(), 1e-9);
}

TEST(BenchView, TableNamesTheViewAndEveryStage) {
  bench::BenchRuns runs;
  runs.repetitions = 1;
  runs.pcl_repetitions = 1;
  const nlohmann::json j = bench::benchView("cube", cube(), runs, unfiltered());
  const std::string t = bench::viewTable(j);
  EXPECT_EQ(t.rfind("\ncube: " + std::to_string(cube().size()) + " px", 0), 0u) << t;
  EXPECT_NE(t.find("K = " + std::to_string(j["keypoints"].get<int>()) + " keypoints"), std::string::npos) << t;
  for (const char* row : {"  filter ", "  histogram ", "  total ", "PCL ISSKeypoint3D", "PCL VFH (+normals)"})
    EXPECT_NE(t.find(row), std::string::npos) << row;
}

TEST(BenchView, AViewThatCannotBeDescribedIsAnError) {
  bench::BenchRuns runs;
  runs.repetitions = 1;
  EXPECT_THROW(bench::benchView("empty", Cloud(), runs, unfiltered()), Error);
}
