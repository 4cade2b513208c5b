// The peers keyturn compares against: ESF made repeatable, VFH and OUR-CVFH
// returning their histograms (OUR-CVFH from a forked worker).
#include "keyturn/core/pcl_baselines.h"

#include <gtest/gtest.h>

#include <chrono>
#include <numeric>
#include <thread>

#include "support/synthetic_clouds.h"

using namespace keyturn;

namespace {

PointSet cylinder() {
  return PointSet::fromCloud(test::unorganized(test::cylinderSurface(0.04f, 0.1f, 60, 30)));
}

}  // namespace

TEST(PclBaselines, SeededEsfRepeatsAcrossSecondsAndChangesWithTheSeed) {
  // PCL's own ESF reseeds from time(): two calls a second apart differ. Seeded ones must not.
  const PointSet set = cylinder();
  const auto a = pclEsfSeeded(set, 7);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  const auto b = pclEsfSeeded(set, 7);
  const auto c = pclEsfSeeded(set, 8);
  ASSERT_EQ(a.size(), 640u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_GT(std::accumulate(a.begin(), a.end(), 0.0), 0.0);
}

TEST(PclBaselines, VfhAndOurCvfhGiveTheirHistograms) {
  const PointSet set = cylinder();
  const auto vfh = pclVfh(set, 0.012);
  const auto cvfh = pclOurCvfh(set, 0.012);
  ASSERT_EQ(vfh.size(), 308u);
  ASSERT_EQ(cvfh.size(), 308u);
  EXPECT_GT(std::accumulate(cvfh.begin(), cvfh.end(), 0.0), 0.0);
  // Same input, same answer from the forked worker.
  EXPECT_EQ(pclOurCvfh(set, 0.012), cvfh);
}
