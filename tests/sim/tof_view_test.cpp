#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

TEST(TofView, RangeNoiseMatchesTheSr4000DatasheetAt2m) {
  // A 99% reflective wall head-on at 2 m: the SR4000 data sheet gives a
  // repeatability (1σ) of about 4 mm there (docs/camera.md).
  sim::Mesh wall;
  wall.vertices = {{-1.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {1.f, 0.f, 1.f}, {-1.f, 0.f, 1.f}};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  sim::TofViewRenderer r(wall);
  sim::SceneView v;
  v.distance = 2.0;
  v.elevation_deg = 0.0;
  v.object_reflectivity = 0.99;
  v.noise = false;
  const Cloud clean = r.render(v);
  EXPECT_NEAR(clean.points[72 * 176 + 88].norm(), 2.0, 0.005);
  v.noise = true;
  const Cloud noisy = r.render(v);
  // 20 × 20 pixels round the centre: independent draws, near-identical σ.
  double sum2 = 0;
  int n = 0;
  for (int row = 62; row < 82; ++row)
    for (int col = 78; col < 98; ++col) {
      const int i = row * 176 + col;
      const double d = noisy.points[i].norm() - clean.points[i].norm();
      sum2 += d * d;
      ++n;
    }
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.004, 0.0006);
}

TEST(TofView, CameraFromTurntableMapsTheObjectOntoItsPixels) {
  const sim::Mesh mug = sim::makeMugMesh();
  sim::TofViewRenderer r(mug);
  sim::SceneView v;
  v.noise = false;
  v.turntable_deg = 0;
  const Cloud c = r.render(v);
  // The mug's outer wall facing the camera (−y side), halfway up.
  const Eigen::Vector4d p_table(0.0, -0.04, 0.05, 1.0);
  const Eigen::Vector4d p_cam = sim::cameraFromTurntable(mug, v) * p_table;
  const auto& k = r.intrinsics();
  const int u = static_cast<int>(std::lround(k.fx * p_cam.x() / p_cam.z() + k.cx - 0.5));
  const int row = static_cast<int>(std::lround(k.fy * p_cam.y() / p_cam.z() + k.cy - 0.5));
  const auto& seen = c.points[row * 176 + u];
  ASSERT_TRUE(Cloud::isValid(seen));
  EXPECT_LT((seen.cast<double>() - p_cam.head<3>()).norm(), 0.006);
}

// A real SR4000's confidence map is graded; the simulated one falls with the range noise σ
// (∝ 1/amplitude): 1/2 where σ is 4 mm, whatever the amplitude threshold.
TEST(TofView, ConfidenceIsGradedByTheRangeNoise) {
  sim::TofViewRenderer r(sim::makeMugMesh());
  for (double threshold : {0.0, 0.02}) {
    sim::SceneView v;
    v.amplitude_threshold = threshold;
    const Cloud c = r.render(v);
    std::vector<std::pair<float, float>> amp_conf;
    for (std::size_t i = 0; i < c.size(); ++i)
      if (Cloud::isValid(c.points[i])) amp_conf.emplace_back(c.amplitude[i], c.confidence[i]);
    ASSERT_GT(amp_conf.size(), 1000u);
    std::sort(amp_conf.begin(), amp_conf.end());
    std::vector<float> levels;
    for (const auto& [amp, conf] : amp_conf) {
      EXPECT_GT(conf, 0.f);
      EXPECT_LT(conf, 1.f);
      // σ = 2 mm × (0.5 / amplitude); confidence = 4 mm / (4 mm + σ).
      EXPECT_NEAR(conf, 0.004 / (0.004 + 0.002 * 0.5 / amp), 1e-5);
      levels.push_back(std::round(conf * 100.f));
    }
    for (std::size_t i = 1; i < amp_conf.size(); ++i) EXPECT_GE(amp_conf[i].second, amp_conf[i - 1].second);
    std::sort(levels.begin(), levels.end());
    EXPECT_GT(std::unique(levels.begin(), levels.end()) - levels.begin(), 20) << "threshold " << threshold;
  }
}
