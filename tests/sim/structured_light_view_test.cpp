// The structured-light sensor model of the simulated OpenNI2 camera
// (keyturn/sim/structured_light_view.h; docs/camera.md gives its sources).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "keyturn/sim/structured_light_view.h"

using namespace keyturn;

namespace {
sim::SceneView still(double distance = 0.8) {
  sim::SceneView v;
  v.distance = distance;
  v.noise = false;
  return v;
}
}  // namespace

TEST(StructuredLight, DepthStepGrowsWithTheSquareOfDepth) {
  const sim::StructuredLightModel m;
  // Δz = z² / (f·b) / 8 with f = 580 px, b = 7.5 cm: 2.87 mm at 1 m, 4× that at 2 m.
  EXPECT_NEAR(sim::depthStep(1.0, 580.0, m), 1.0 / (580.0 * 0.075) / 8.0, 1e-12);
  EXPECT_NEAR(sim::depthStep(1.0, 580.0, m) * 1000, 2.874, 0.001);
  EXPECT_NEAR(sim::depthStep(2.0, 580.0, m) / sim::depthStep(1.0, 580.0, m), 4.0, 1e-9);
  // Nguyen et al.: 1.2 mm + 1.9 mm·(z − 0.4)² head-on, much more at grazing incidence.
  EXPECT_NEAR(sim::axialSigma(1.0, 0.0, m), 0.0012 + 0.0019 * 0.36, 1e-12);
  EXPECT_GT(sim::axialSigma(1.0, 1.3, m), 2 * sim::axialSigma(1.0, 0.0, m));
}

TEST(StructuredLight, DepthsLieOnTheDisparityLatticeWithinRange) {
  sim::StructuredLightRenderer r(sim::makeMugMesh());
  const auto f = r.render(still());
  ASSERT_EQ(f.width, 640);
  ASSERT_EQ(f.height, 480);
  const double fb = 580.0 * 0.075;
  int valid = 0, off_lattice = 0;
  for (float z : f.depth) {
    if (z == 0.f) continue;
    ++valid;
    EXPECT_GE(z, 0.5f);
    EXPECT_LE(z, 4.5f);
    const double eighths = fb / z * 8.0;  // disparity in 1/8 px: a whole number
    if (std::abs(eighths - std::round(eighths)) > 1e-3 * eighths) ++off_lattice;
  }
  EXPECT_GT(valid, 100000);  // the table fills most of the view
  EXPECT_EQ(off_lattice, 0);
}

// A pixel whose surface point the projector (7.5 cm to the camera's right) cannot
// see has no depth; such pixels lie just left of the object, where the object
// hides the table from the projector. A light at the lens casts no visible shadow.
TEST(StructuredLight, ProjectorShadowsLieBesideTheObjectsLeftEdge) {
  sim::StructuredLightModel m;
  m.max_incidence_deg = 90;  // count only the projector's shadow
  sim::StructuredLightRenderer r(sim::makeMugMesh(), sim::kinectIntrinsics(), m);
  sim::TofViewRenderer geometry(sim::makeMugMesh(), sim::kinectIntrinsics());
  const auto f = r.render(still());
  const auto s = geometry.castPixelCentres(still(), Eigen::Vector3f(0.075f, 0, 0));
  int shadowed = 0, left_of_object = 0, measured = 0;
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * 640 + u;
      if (s[i].depth <= 0) continue;
      if (s[i].lit) {
        measured += f.depth[i] > 0;
        continue;
      }
      ++shadowed;
      EXPECT_EQ(f.depth[i], 0.f) << "shadowed pixel " << u << "," << v << " has depth";
      // The object's edge within 20 px to the right, the pixel itself not on it.
      bool right = false;
      for (int d = 1; d <= 20 && u + d < 640; ++d) right |= s[i + d].object;
      if (right && !s[i].object) ++left_of_object;
    }
  }
  std::printf("%d shadowed pixels, %d of them just left of the object; %d lit pixels measured\n", shadowed,
              left_of_object, measured);
  EXPECT_GT(shadowed, 200);
  EXPECT_GT(left_of_object, 0.9 * shadowed);
  EXPECT_GT(measured, 100000);
  int at_lens = 0;
  for (const auto& p : geometry.castPixelCentres(still(), Eigen::Vector3f::Zero())) at_lens += p.depth > 0 && !p.lit;
  EXPECT_EQ(at_lens, 0);
}

TEST(StructuredLight, WorkingRangeCutsNearAndFar) {
  sim::StructuredLightRenderer r(sim::makeMugMesh());
  auto valid = [&](double distance) {
    const auto f = r.render(still(distance));
    int n = 0;
    for (float z : f.depth) n += z > 0;
    return n;
  };
  EXPECT_GT(valid(0.8), 100000);
  EXPECT_EQ(valid(6.0), 0);  // the whole table beyond 4.5 m
  // Nearer than 0.5 m the mug is lost, though the table beyond it is measured.
  const auto near = r.render(still(0.3));
  EXPECT_EQ(near.depth[240 * 640 + 320], 0.f);
  EXPECT_GT(r.render(still(0.8)).depth[240 * 640 + 320], 0.f);
}

TEST(StructuredLight, NoiseIsSeededAndMatchesTheAxialModel) {
  sim::StructuredLightRenderer r(sim::makeMugMesh());
  sim::SceneView v = still(1.5);
  v.noise = true;
  v.seed = 3;
  const auto a = r.render(v), b = r.render(v);
  EXPECT_EQ(a.depth, b.depth);
  v.seed = 4;
  EXPECT_NE(r.render(v).depth, a.depth);
  // The centre pixel (on the mug, head-on) over many frames: σ as the model says.
  const std::size_t c = 240 * 640 + 320;
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int seed = 0; seed < 200; ++seed) {
    v.seed = static_cast<std::uint64_t>(seed);
    const double z = r.render(v).depth[c];
    if (z <= 0) continue;
    sum += z;
    sum2 += z * z;
    ++n;
  }
  ASSERT_GT(n, 150);
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  const double expect = sim::axialSigma(mean, 0.0, r.model());  // ≈ 3.3 mm at 1.46 m; disparity step 6 mm
  EXPECT_GT(sd, 0.6 * expect);
  EXPECT_LT(sd, 2.5 * expect);
}

TEST(StructuredLight, ColourAndIrFollowTheScene) {
  sim::StructuredLightRenderer r(sim::makeMugMesh());
  const auto f = r.render(still());
  const std::size_t c = 240 * 640 + 320;
  // The mug is orange-ish, the table grey, the empty view dark; IR is lit where depth is measured.
  EXPECT_GT(f.rgb[3 * c], f.rgb[3 * c + 2] + 40);
  EXPECT_GT(f.ir[c], 0);
  EXPECT_LE(f.ir[c], 1023);
}

// The cast finds the table without Embree where a ray misses the sphere around the turning object
// (the simulated camera's speed while the table turns: tests/bench BM_RenderStructuredLightTurning).
// It must find what Embree finds, pixel for pixel: the table's depth, the object, the shadows.
TEST(StructuredLight, TheTableFoundWithoutEmbreeIsTheTableEmbreeFinds) {
  for (const char* mesh : {"builtin", KEYTURN_DATA_DIR "/objects/drill__ycb_035_power_drill.ply",
                           KEYTURN_DATA_DIR "/objects/bowl__ycb_024_bowl.ply"}) {
    const sim::Mesh m = std::string(mesh) == "builtin" ? sim::makeMugMesh() : sim::loadMesh(mesh);
    sim::TofViewRenderer r(m, sim::kinectIntrinsics());
    for (double elevation : {10.0, 30.0, 60.0}) {
      for (double angle : {0.0, 37.0, 200.0}) {
        sim::SceneView v = still(0.9);
        v.elevation_deg = elevation;
        v.turntable_deg = angle;
        const Eigen::Vector3f projector(0.075f, 0.f, 0.f);
        const auto fast = r.castPixelCentres(v, projector);
        const auto reference = r.castPixelCentres(v, projector, true);
        ASSERT_EQ(fast.size(), reference.size());
        int table = 0, object = 0, shadowed = 0, differ = 0;
        for (std::size_t i = 0; i < fast.size(); ++i) {
          const sim::SurfacePixel &a = fast[i], &b = reference[i];
          table += b.depth > 0 && !b.object;
          object += b.object;
          shadowed += b.depth > 0 && !b.lit;
          differ += a.object != b.object || a.lit != b.lit || std::abs(a.depth - b.depth) > 1e-5f ||
                    std::abs(a.cos_incidence - b.cos_incidence) > 1e-4f || std::abs(a.cos_light - b.cos_light) > 1e-4f;
        }
        EXPECT_EQ(differ, 0) << mesh << " at elevation " << elevation << "°, turntable " << angle << "°";
        // The views have all three: table, object and the projector's shadow on the table.
        EXPECT_GT(table, 10000);
        EXPECT_GT(object, 500);
        EXPECT_GT(shadowed, 20);
      }
    }
  }
}

// A camera opened prepares its view (the simulated OpenNI2 device does, issue 51): the first frame
// then casts nothing, draws only noise, and is the frame an unprepared renderer gives for the view.
TEST(StructuredLight, APreparedViewRendersWithoutCastingAgain) {
  const sim::Mesh mug = sim::makeMugMesh();
  sim::StructuredLightRenderer prepared(mug), cold(mug);
  sim::SceneView v = still(0.9);
  v.noise = true;
  v.seed = 11;
  EXPECT_EQ(prepared.casts(), 0u);
  prepared.prepare(v);
  EXPECT_EQ(prepared.casts(), 1u);
  const auto first = prepared.render(v);
  EXPECT_EQ(prepared.casts(), 1u);
  EXPECT_EQ(first.depth, cold.render(v).depth);
  EXPECT_EQ(first.rgb, cold.render(v).rgb);
  v.seed = 12;  // another frame of the still scene: noise only
  prepared.render(v);
  prepared.prepare(v);
  EXPECT_EQ(prepared.casts(), 1u);
  v.turntable_deg = 10;  // the table turned: cast again
  prepared.render(v);
  EXPECT_EQ(prepared.casts(), 2u);
}
