#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "keyturn/core/shape_distributions.h"

using namespace keyturn;

namespace {
std::vector<Eigen::Vector3f> sphere(int n, float r) {
  std::mt19937 rng(11);
  std::normal_distribution<float> g;
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < n; ++i) pts.push_back(r * Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized());
  return pts;
}
double mean(const std::vector<float>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); }
}  // namespace

TEST(Osada, D1OnASphereIsItsRadius) {
  const auto v = osadaShapeFunction(sphere(5000, 0.2f), OsadaFunction::D1, OsadaOptions());
  EXPECT_NEAR(mean(v), 0.2, 0.005);
}

TEST(Osada, D2OnASphereHasMeanFourThirdsRadius) {
  // Mean chord between uniform points on a sphere of radius R is 4R/3.
  OsadaOptions o;
  o.samples = 100000;
  const auto v = osadaShapeFunction(sphere(20000, 0.3f), OsadaFunction::D2, o);
  EXPECT_NEAR(mean(v), 0.4, 0.006);
}

TEST(Osada, A3AnglesAreInRangeAndSeedable) {
  OsadaOptions o;
  o.seed = 5;
  const auto pts = sphere(500, 1.f);
  const auto a = osadaShapeFunction(pts, OsadaFunction::A3, o);
  const auto b = osadaShapeFunction(pts, OsadaFunction::A3, o);
  EXPECT_EQ(a, b);
  for (float x : a) {
    EXPECT_GE(x, 0.f);
    EXPECT_LE(x, static_cast<float>(M_PI) + 1e-6f);
  }
  o.seed = 6;
  EXPECT_NE(osadaShapeFunction(pts, OsadaFunction::A3, o), a);
}

TEST(Osada, D3AndD4OfAFlatSetAreBounded) {
  std::vector<Eigen::Vector3f> flat;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) flat.emplace_back(0.01f * i, 0.01f * j, 0.f);
  for (float v : osadaShapeFunction(flat, OsadaFunction::D4, OsadaOptions())) EXPECT_NEAR(v, 0.f, 1e-5f);
  // The largest triangle in a 0.29 m square has area 0.29²/2.
  for (float v : osadaShapeFunction(flat, OsadaFunction::D3, OsadaOptions()))
    EXPECT_LE(v, std::sqrt(0.29f * 0.29f / 2) + 1e-5f);
}
