#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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
