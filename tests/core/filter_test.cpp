#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <string>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/filter.h"
#include "support/synthetic_clouds.h"

using namespace keyturn;

TEST(JumpEdge, RemovesMixedPixelsBetweenTwoSurfaces) {
  Cloud c = test::organizedPlanes(40, 30, 50.f, 1.5f, 1.0f, 10, 30, 8, 22);
  // Put mixed pixels on the left border of the front rectangle: halfway in depth.
  const int w = 40;
  for (int v = 8; v < 22; ++v) {
    const int u = 9;
    const float z = 1.25f;
    c.points[v * w + u] = Eigen::Vector3f((u + 0.5f - 20.f) / 50.f * z, (v + 0.5f - 15.f) / 50.f * z, z);
  }
  const std::size_t removed = removeJumpEdges(c, 10.f);
  for (int v = 9; v < 21; ++v) EXPECT_FALSE(Cloud::isValid(c.points[v * w + 9])) << "mixed pixel row " << v;
  // Interior pixels of both planes survive.
  EXPECT_TRUE(Cloud::isValid(c.points[15 * w + 20]));
  EXPECT_TRUE(Cloud::isValid(c.points[2 * w + 2]));
  EXPECT_GE(removed, 14u);
  EXPECT_LT(removed, 200u);  // only the borders, not whole planes
}

TEST(JumpEdge, FlatPlaneKeepsEveryPixel) {
  Cloud c = test::organizedPlanes(30, 20, 40.f, 1.0f, 1.0f, 0, 0, 0, 0);
  EXPECT_EQ(removeJumpEdges(c, 10.f), 0u);
}

TEST(PlaneRemoval, RemovesTheTableKeepsTheObject) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) pts.emplace_back(-0.3f + 0.01f * i, 0.2f, 0.6f + 0.01f * j);  // y = 0.2 plane
  const auto cube = test::cubeSurface(0.1f, 12, Eigen::Vector3f(0.f, 0.14f, 0.9f));
  pts.insert(pts.end(), cube.begin(), cube.end());
  Cloud c = test::unorganized(pts);
  FilterOptions o;
  Eigen::Vector4f plane;
  ASSERT_TRUE(removeDominantPlane(c, o, &plane));
  EXPECT_NEAR(std::abs(plane[1]), 1.f, 1e-3f);
  EXPECT_NEAR(std::abs(plane[3]), 0.2f, 1e-3f);
  const std::size_t left = c.validCount();
  // The cube's bottom face sits 1 cm above the table: all but it survives.
  EXPECT_GT(left, cube.size() * 3 / 4);
  EXPECT_LE(left, cube.size());
}

TEST(OutlierRemoval, DropsIsolatedPointsOnly) {
  auto pts = test::cubeSurface(0.1f, 15, Eigen::Vector3f(0, 0, 1));
  const std::size_t surface = pts.size();
  pts.emplace_back(0.3f, 0.3f, 1.3f);
  pts.emplace_back(-0.4f, 0.2f, 0.8f);
  Cloud c = test::unorganized(pts);
  removeStatisticalOutliers(c, 10, 2.0f);
  EXPECT_FALSE(Cloud::isValid(c.points[surface]));
  EXPECT_FALSE(Cloud::isValid(c.points[surface + 1]));
  EXPECT_GE(c.validCount(), surface * 95 / 100);
}

TEST(Cluster, KeepsTheLargestComponent) {
  auto pts = test::cubeSurface(0.1f, 12, Eigen::Vector3f(0, 0, 1));
  const std::size_t big = pts.size();
  for (const auto& p : test::cubeSurface(0.02f, 4, Eigen::Vector3f(0.3f, 0, 1))) pts.push_back(p);
  Cloud c = test::unorganized(pts);
  keepLargestCluster(c, 0.015f);
  EXPECT_EQ(c.validCount(), big);
}

// The cluster step against every pair of points: a real crop, thinned, with 300 stray points
// scattered around it (many small components, some touching the object, some chains), at
// tolerances from below to above the points' spacing.
TEST(Cluster, KeepsExactlyTheLargestComponentOfTheToleranceGraph) {
  const Cloud crop = loadCloud(std::string(KEYTURN_REAL_DATA) + "/crop/learn0_o1.pcd");
  std::vector<Eigen::Vector3f> pts;
  for (std::size_t i = 0; i < crop.points.size(); i += 5)
    if (Cloud::isValid(crop.points[i])) pts.push_back(crop.points[i]);
  Eigen::AlignedBox3f box;
  for (const auto& p : pts) box.extend(p);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3f f(u(rng), u(rng), u(rng));
    pts.push_back(box.min() - Eigen::Vector3f::Constant(0.05f) +
                  f.cwiseProduct(box.sizes() + Eigen::Vector3f::Constant(0.1f)));
  }
  const int n = static_cast<int>(pts.size());
  for (float t : {0.004f, 0.009f, 0.015f, 0.03f}) {
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int v) { return parent[v] == v ? v : parent[v] = find(parent[v]); };
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if ((pts[i] - pts[j]).squaredNorm() < t * t) parent[find(i)] = find(j);
    std::vector<int> size(n, 0);
    for (int i = 0; i < n; ++i) ++size[find(i)];
    int best = find(0);
    for (int i = 0; i < n; ++i)
      if (size[find(i)] > size[best]) best = find(i);  // ties: the lowest point index, as the step
    Cloud c = test::unorganized(pts);
    keepLargestCluster(c, t);
    int components = 0;
    for (int i = 0; i < n; ++i) {
      components += find(i) == i;
      EXPECT_EQ(Cloud::isValid(c.points[static_cast<std::size_t>(i)]), find(i) == best) << "t " << t << ", point " << i;
    }
    EXPECT_GT(components, 10) << "t " << t << ": the test needs several components";
  }
}

TEST(CropRange, DropsPointsOutsideTheRange) {
  Cloud c = test::unorganized({{0, 0, 0.05f}, {0, 0, 1.f}, {0, 0, 4.f}});
  cropRange(c, 0.1f, 3.f);
  EXPECT_EQ(c.validCount(), 1u);
  EXPECT_TRUE(Cloud::isValid(c.points[1]));
}

namespace {

// The faces of a box (centre c, half sizes h) that a camera at the origin sees.
std::vector<Eigen::Vector3f> visibleBoxFaces(const Eigen::Vector3f& c, const Eigen::Vector3f& h, float step) {
  std::vector<Eigen::Vector3f> pts;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      n[axis] = static_cast<float>(sign);
      const Eigen::Vector3f centre = c + n.cwiseProduct(h);
      if (n.dot(-centre) <= 0.f) continue;  // faces away from the camera
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (float u = -h[a]; u <= h[a]; u += step)
        for (float v = -h[b]; v <= h[b]; v += step) {
          Eigen::Vector3f p = centre;
          p[a] += u;
          p[b] += v;
          pts.push_back(p);
        }
    }
  return pts;
}

}  // namespace

// A segmented box (no table): its largest face is the dominant plane, but the rest of
// the box lies behind that face, so it is not a support and stays.
TEST(SupportRule, KeepsTheLargestFaceOfASegmentedBox) {
  // Seen from above and the side: front (z-), top (y-) and left (x-) faces visible.
  const auto pts = visibleBoxFaces({0.15f, 0.12f, 0.9f}, {0.12f, 0.04f, 0.08f}, 0.003f);
  Cloud c = test::unorganized(pts);
  FilterOptions o;
  std::string why;
  EXPECT_FALSE(removeDominantPlane(c, o, nullptr, &why));
  EXPECT_EQ(c.validCount(), pts.size());
  EXPECT_NE(why.find("behind"), std::string::npos) << why;
  // Through the whole filter: every step keeps (nearly) the whole box, nothing is flagged.
  FilterReport r;
  const Cloud out = filterCloud(test::unorganized(pts), o, &r);
  EXPECT_EQ(r.kind, InputKind::SegmentedCloud);
  EXPECT_FALSE(r.plane_found);
  EXPECT_GT(out.validCount(), pts.size() * 95 / 100);
  EXPECT_FALSE(r.anyFlagged()) << r.flaggedSummary();
}

// The same box standing on a table: the table is a support and goes, the box stays.
TEST(SupportRule, RemovesTheTableUnderTheBox) {
  const Eigen::Vector3f c(0.f, 0.16f, 0.9f), h(0.06f, 0.04f, 0.05f);  // y down: the table is y = 0.2
  auto pts = visibleBoxFaces(c, h, 0.003f);
  const std::size_t box = pts.size();
  for (float x = -0.3f; x <= 0.3f; x += 0.005f)
    for (float z = 0.6f; z <= 1.2f; z += 0.005f)
      if (std::abs(x) > h.x() || std::abs(z - c.z()) > h.z()) pts.emplace_back(x, 0.2f, z);
  Cloud cloud = test::unorganized(pts);
  std::string why;
  ASSERT_TRUE(removeDominantPlane(cloud, FilterOptions(), nullptr, &why)) << why;
  EXPECT_GT(cloud.validCount(), box * 85 / 100);  // the bottom strip of the faces is within the band
  EXPECT_LE(cloud.validCount(), box);
}

// A plate's flat floor with its rim rising towards the camera: in front of the plane,
// but spread wider than it, so the floor is the object, not a support.
TEST(PlaneRemoval, PclPrintsNothingWhereNoPlaneFits) {
  // Twelve points on a twisted cubic, no four of them on a plane: PCL's RANSAC found its best plane
  // through three and wrote "[pcl::SampleConsensusModelPlane::optimizeModelCoefficients] Not enough
  // inliers found to optimize model coefficients (3)! …" to stderr, beside keyturn's own messages.
  std::vector<Eigen::Vector3f> twisted;
  for (int i = 0; i < 12; ++i) {
    const float t = -1.f + 2.f * static_cast<float>(i) / 11.f;
    twisted.push_back(2.f * Eigen::Vector3f(t, t * t, 2.f + t * t * t));  // 4 m across: 8 mm planes hold 3
  }
  Cloud c = test::unorganized(twisted);
  std::string why;
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(removeDominantPlane(c, FilterOptions(), nullptr, &why));
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << why;
  EXPECT_EQ(c.validCount(), 12u);
}

TEST(SupportRule, KeepsAPlatesFloor) {
  std::vector<Eigen::Vector3f> pts;
  for (float x = -0.08f; x <= 0.08f; x += 0.003f)
    for (float z = -0.08f; z <= 0.08f; z += 0.003f) {
      const float r = std::hypot(x, z);
      if (r > 0.12f) continue;
      pts.emplace_back(x, 0.2f, 0.9f + z);  // floor, radius 8 cm (square-ish patch)
    }
  for (float a = 0.f; a < 6.283f; a += 0.02f)
    for (float r = 0.09f; r <= 0.12f; r += 0.003f)
      pts.emplace_back(r * std::cos(a), 0.2f - 0.8f * (r - 0.085f), 0.9f + r * std::sin(a));  // rim, rising
  Cloud c = test::unorganized(pts);
  std::string why;
  EXPECT_FALSE(removeDominantPlane(c, FilterOptions(), nullptr, &why)) << why;
  EXPECT_NE(why.find("narrower"), std::string::npos) << why;
}

TEST(FilterReport, NamesTheInputKindAndCountsEveryStep) {
  Cloud frame = test::organizedPlanes(60, 40, 50.f, 1.5f, 1.0f, 20, 40, 10, 30);
  FilterReport r;
  filterCloud(frame, FilterOptions(), &r);
  EXPECT_EQ(r.kind, InputKind::Frame);
  ASSERT_EQ(r.steps.size(), 5u);
  EXPECT_EQ(r.steps[0].name, "crop");
  EXPECT_EQ(r.steps[0].before, 2400u);
  for (std::size_t k = 1; k < r.steps.size(); ++k) EXPECT_EQ(r.steps[k].before, r.steps[k - 1].after);
  // Masked: only the front rectangle valid (400 of 2400 pixels < 30 %).
  Cloud masked = frame;
  for (std::size_t i = 0; i < masked.size(); ++i)
    if (masked.points[i].z() > 1.2f) masked.points[i].setConstant(std::nanf(""));
  EXPECT_EQ(classifyInput(masked), InputKind::MaskedFrame);
  EXPECT_EQ(classifyInput(test::unorganized({{0, 0, 1}, {0, 0.1f, 1}})), InputKind::SegmentedCloud);
}

// An unorganized cloud's frame is unknown: the range crop (metres from the camera) is not applied,
// so an object cloud centred on the origin survives.
TEST(FilterReport, DoesNotRangeCropASegmentedCloud) {
  const auto pts = test::cubeSurface(0.1f, 12, Eigen::Vector3f(0, 0, 0));
  FilterReport r;
  const Cloud out = filterCloud(test::unorganized(pts), FilterOptions(), &r);
  EXPECT_FALSE(r.steps[0].applied);
  EXPECT_GT(out.validCount(), pts.size() * 9 / 10);
}

// A step that removes more than half of what it was given, where that is not its job, is flagged.
TEST(FilterReport, FlagsAStepThatRemovesMostOfTheView) {
  Cloud frame = test::organizedPlanes(60, 40, 50.f, 1.5f, 1.0f, 20, 40, 10, 30);
  FilterOptions o;
  o.max_range = 1.2f;  // the back plane (5/6 of the pixels) lies beyond
  FilterReport r;
  filterCloud(frame, o, &r);
  EXPECT_TRUE(r.steps[0].flagged);
  EXPECT_NE(r.flaggedSummary().find("crop removed 83%"), std::string::npos) << r.flaggedSummary();
  o.max_range = 3.f;
  filterCloud(frame, o, &r);
  EXPECT_FALSE(r.steps[0].flagged);
}
