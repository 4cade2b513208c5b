#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/sim/tof_view.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

TEST(RadiusSearch, GridMatchesKdTreeOnARenderedView) {
  sim::TofViewRenderer renderer(sim::makeMugMesh());
  sim::SceneView view;
  view.turntable_deg = 20;
  const PointSet set = PointSet::fromCloud(renderer.render(view));
  ASSERT_GT(set.size(), 10000u);
  const RadiusSearch grid(set);
  ASSERT_TRUE(grid.usesGrid());
  const auto tree = RadiusSearch::kdTree(set);
  std::vector<int> a, b;
  std::size_t total = 0;
  for (std::size_t i = 0; i < set.size(); i += 7) {
    for (float r : {0.004f, 0.012f}) {
      grid.radius(static_cast<int>(i), r, a);
      tree->radius(static_cast<int>(i), r, b);
      ASSERT_EQ(a, b) << "point " << i << " radius " << r;
      total += a.size();
    }
    EXPECT_FLOAT_EQ(grid.nearestDistance(static_cast<int>(i)), tree->nearestDistance(static_cast<int>(i)));
  }
  EXPECT_GT(total, set.size());  // the searches did find neighbours
}

TEST(RadiusSearch, ResolutionOfARegularGridIsItsSpacing) {
  // A fronto-parallel plane at 1 m seen with f = 200 px: spacing 5 mm.
  const Cloud c = test::organizedPlanes(40, 30, 200.f, 1.0f, 1.0f, 0, 0, 0, 0);
  const PointSet set = PointSet::fromCloud(c);
  EXPECT_NEAR(cloudResolution(set), 0.005, 1e-5);
  const Cloud u = test::unorganized(set.points);
  EXPECT_NEAR(cloudResolution(PointSet::fromCloud(u)), 0.005, 1e-5);
}

TEST(RadiusSearch, ResolutionNeedsTwoPoints) {
  const PointSet one = PointSet::fromCloud(test::unorganized({Eigen::Vector3f(0, 0, 1)}));
  EXPECT_THROW(cloudResolution(one), std::runtime_error);
}

// The neighbourhood table of an unorganized set (a hash grid, filled cell by cell): every cached
// row equals a k-d tree's search, in ascending index order, on a real crop and a random cloud.
TEST(RadiusSearch, CachedRowsOfAnUnorganizedSetMatchTheKdTree) {
  std::vector<Eigen::Vector3f> random;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.1f, 0.1f);
  for (int i = 0; i < 3000; ++i) random.emplace_back(u(rng), u(rng), 1.f + u(rng));
  std::vector<PointSet> sets = {PointSet::fromCloud(test::unorganized(random))};
#ifdef KEYTURN_REAL_DATA
  sets.push_back(PointSet::fromCloud(loadCloud(std::string(KEYTURN_REAL_DATA) + "/crop/learn0_o1.pcd")));
#endif
  for (const PointSet& set : sets) {
    RadiusSearch cached(set);
    ASSERT_FALSE(cached.usesGrid());
    const double res = cloudResolution(set, cached);
    cached.cacheNeighbourhoods(static_cast<float>(6 * res));
    const auto tree = RadiusSearch::kdTree(set);
    std::vector<int> a, b;
    std::size_t total = 0;
    for (std::size_t i = 0; i < set.size(); i += 3)
      for (double m : {2.0, 6.0}) {
        const float r = static_cast<float>(m * res);
        cached.radius(static_cast<int>(i), r, a);
        tree->radius(static_cast<int>(i), r, b);
        ASSERT_EQ(a, b) << "point " << i << ", radius " << r;
        total += a.size();
      }
    EXPECT_GT(total, 10 * set.size() / 3) << "the rows should hold many neighbours";
    // The rows' squared distances are the Eigen formula's floats, bit for bit (the table computes
    // them in vectorised rows): the nearest distance read from them is that of every pair.
    std::size_t differ = 0;
    for (std::size_t i = 0; i < set.size(); i += 7) {
      float best = std::numeric_limits<float>::infinity();
      for (std::size_t j = 0; j < set.size(); ++j)
        if (j != i) best = std::min(best, (set.points[j] - set.points[i]).squaredNorm());
      differ += cached.nearestDistance(static_cast<int>(i)) != std::sqrt(best);
    }
    EXPECT_EQ(differ, 0u);
  }
}
