#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

TEST(CropRange, DropsPointsOutsideTheRange) {
  Cloud c = test::unorganized({{0, 0, 0.05f}, {0, 0, 1.f}, {0, 0, 4.f}});
  cropRange(c, 0.1f, 3.f);
  EXPECT_EQ(c.validCount(), 1u);
  EXPECT_TRUE(Cloud::isValid(c.points[1]));
}
