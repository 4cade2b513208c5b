#include <gtest/gtest.h>

#include <cmath>

#include "keyturn/core/error.h"
#include "keyturn/sim/tof_view.h"

using namespace keyturn;

TEST(TofView, FrameGeometryMatchesTheSr4000Intrinsics) {
  sim::TofViewRenderer r(sim::makeMugMesh());
  sim::SceneView v;
  v.noise = false;
  const Cloud c = r.render(v);
  ASSERT_EQ(c.width, 176u);
  ASSERT_EQ(c.height, 144u);
  const auto& k = r.intrinsics();
  std::size_t checked = 0;
  for (int px = 0; px < 176 * 144; px += 97) {
    const auto& p = c.points[px];
    if (!Cloud::isValid(p)) continue;
    const double u = k.fx * p.x() / p.z() + k.cx - 0.5, vv = k.fy * p.y() / p.z() + k.cy - 0.5;
    EXPECT_NEAR(u, px % 176, 1e-3);
    EXPECT_NEAR(vv, px / 176, 1e-3);
    ++checked;
  }
  EXPECT_GT(checked, 100u);
}

TEST(TofView, ObjectCentreIsAtTheChosenDistance) {
  sim::TofViewRenderer r(sim::makeMugMesh());
  sim::SceneView v;
  v.noise = false;
  v.distance = 0.6;
  const Cloud c = r.render(v);
  // The centre pixel looks at the mug's mid-height on its axis: its front wall
  // is one outer radius (4 cm) nearer, give or take the elevation.
  const auto& p = c.points[72 * 176 + 88];
  ASSERT_TRUE(Cloud::isValid(p));
  EXPECT_NEAR(p.norm(), 0.6 - 0.04, 0.01);
}

TEST(TofView, NoiseIsSeededAndGrowsWithDistance) {
  sim::TofViewRenderer r(sim::makeMugMesh());
  sim::SceneView v;
  v.seed = 9;
  const Cloud a = r.render(v), b = r.render(v);
  EXPECT_EQ(a.points[72 * 176 + 88], b.points[72 * 176 + 88]);
  auto spread = [&](double dist) {
    sim::SceneView s;
    s.distance = dist;
    s.noise = false;
    const Cloud clean = r.render(s);
    s.noise = true;
    double sum2 = 0;
    int n = 0;
    for (int seed = 0; seed < 20; ++seed) {
      s.seed = seed;
      const Cloud noisy = r.render(s);
      const auto& p = noisy.points[72 * 176 + 88];
      const auto& q = clean.points[72 * 176 + 88];
      if (!Cloud::isValid(p) || !Cloud::isValid(q)) continue;
      sum2 += (p - q).squaredNorm();
      ++n;
    }
    return std::sqrt(sum2 / n);
  };
  const double near = spread(0.5), far = spread(2.0);
  EXPECT_GT(far, 4 * near);  // σ ∝ 1/amplitude ∝ d²
  EXPECT_LT(near, 0.003);
}

TEST(TofView, MissingMeshIsAClearError) {
  try {
    sim::loadMesh("/nonexistent/mesh.ply");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/mesh.ply"), std::string::npos);
  }
}
