#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "keyturn/core/keypoint_functions.h"

using namespace keyturn;

namespace {
// A 3-4-5 right triangle in the xy plane plus an apex above the origin.
const std::vector<Eigen::Vector3f> kPts = {{0, 0, 0}, {3, 0, 0}, {0, 4, 0}, {0, 0, 2}};
}

TEST(Kpd2, AllPairDistances) {
  auto d = keypointDistances(kPts);
  std::sort(d.begin(), d.end());
  const std::vector<float> expect = {2.f, 3.f, 4.f, 5.f, std::sqrt(13.f), std::sqrt(20.f)};
  std::vector<float> e = expect;
  std::sort(e.begin(), e.end());
  ASSERT_EQ(d.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(d[i], e[i], 1e-5f);
}

TEST(Kpd3, SqrtTriangleAreas) {
  auto a = keypointSqrtAreas(kPts);
  ASSERT_EQ(a.size(), 4u);
  // Triangles: (0,1,2) area 6; (0,1,3) 3; (0,2,3) 4; (1,2,3): |(−3,4,0)×(−3,0,2)|/2.
  const float a123 = 0.5f * Eigen::Vector3f(-3, 4, 0).cross(Eigen::Vector3f(-3, 0, 2)).norm();
  std::vector<float> e = {std::sqrt(6.f), std::sqrt(3.f), std::sqrt(4.f), std::sqrt(a123)};
  std::sort(a.begin(), a.end());
  std::sort(e.begin(), e.end());
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(a[i], e[i], 1e-5f);
}

TEST(Kpa3, EveryInteriorAngleOfEveryTriangle) {
  const auto ang = keypointAngles(kPts);
  ASSERT_EQ(ang.size(), 12u);
  // Each consecutive triple is one triangle: its angles sum to π.
  for (std::size_t t = 0; t < 4; ++t) EXPECT_NEAR(ang[3 * t] + ang[3 * t + 1] + ang[3 * t + 2], M_PI, 1e-5);
  // Triangle (0,1,2): right angle at vertex 0, atan(4/3) at 1, atan(3/4) at 2.
  EXPECT_NEAR(ang[0], M_PI / 2, 1e-5);
  EXPECT_NEAR(ang[1], std::atan(4.0 / 3.0), 1e-5);
  EXPECT_NEAR(ang[2], std::atan(3.0 / 4.0), 1e-5);
}

TEST(Kpa3, DegenerateTriangleWithRepeatedPointIsSkipped) {
  const auto ang = keypointAngles({{0, 0, 0}, {0, 0, 0}, {1, 0, 0}});
  EXPECT_TRUE(ang.empty());
}

TEST(KeypointFunctions, CountsGrowAsPairsAndTriples) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 20; ++i) pts.emplace_back(std::cos(i * 0.7f), std::sin(i * 1.3f), 0.1f * i);
  EXPECT_EQ(keypointDistances(pts).size(), 190u);
  EXPECT_EQ(keypointSqrtAreas(pts).size(), 1140u);
  EXPECT_EQ(keypointAngles(pts).size(), 3420u);
}

// keypointAngles computes its cosines in vectorised rows; each must be, bit for bit, the scalar
// Eigen formula the angle is defined by, for the angle at every corner of every triangle.
TEST(Kpa3, AnglesAreBitForBitTheEigenFormula) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.2f, 0.2f);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 37; ++i) pts.emplace_back(u(rng), u(rng), 0.8f + u(rng));
  pts.push_back(pts[3]);  // a coincident pair: its triangles are skipped
  auto angle = [](const Eigen::Vector3f& p, const Eigen::Vector3f& q) {
    return std::acos(std::clamp(p.dot(q) / std::sqrt(p.squaredNorm() * q.squaredNorm()), -1.0f, 1.0f));
  };
  std::vector<float> expected;
  for (std::size_t a = 0; a < pts.size(); ++a)
    for (std::size_t b = a + 1; b < pts.size(); ++b)
      for (std::size_t c = b + 1; c < pts.size(); ++c) {
        const Eigen::Vector3f ab = pts[b] - pts[a], ac = pts[c] - pts[a], bc = pts[c] - pts[b];
        if (ab.squaredNorm() <= 0.f || ac.squaredNorm() <= 0.f || bc.squaredNorm() <= 0.f) continue;
        expected.push_back(angle(ab, ac));
        expected.push_back(angle(-ab, bc));
        expected.push_back(angle(-ac, -bc));
      }
  const auto got = keypointAngles(pts);
  ASSERT_EQ(got.size(), expected.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < got.size(); ++i) differ += got[i] != expected[i];
  EXPECT_EQ(differ, 0u) << "of " << got.size() << " angles";
}

// KPA3's PDF binned from a rough arccos where it cannot be wrong is exactly the histogram of
// keypointAngles: on random sets, on a regular grid (many angles exactly on bin edges: 45°, 90°
// at 8 or 16 bins), at several bin counts and on a range narrower than [0, π] (clamping).
TEST(Kpa3, PdfIsExactlyTheHistogramOfTheAngles) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.1f, 0.1f);
  std::vector<std::vector<Eigen::Vector3f>> sets;
  for (int s = 0; s < 4; ++s) {
    std::vector<Eigen::Vector3f> pts;
    for (int i = 0; i < 40; ++i) pts.emplace_back(u(rng), u(rng), 0.5f + 0.3f * u(rng));
    sets.push_back(pts);
  }
  std::vector<Eigen::Vector3f> grid;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) grid.emplace_back(0.01f * i, 0.01f * j, 0.f);
  sets.push_back(grid);
  for (const auto& pts : sets)
    for (int bins : {1, 8, 16, 32, 90})
      for (const HistogramRange range : {HistogramRange{0.0, M_PI}, HistogramRange{0.3, 2.0}}) {
        const auto fast = keypointAnglePdf(pts, bins, range);
        const auto exact = histogramPdf(keypointAngles(pts), bins, range);
        EXPECT_EQ(fast, exact) << bins << " bins, range " << range.lo << "–" << range.hi;
      }
  EXPECT_EQ(keypointAnglePdf({}, 32, {0.0, M_PI}), std::vector<double>(32, 0.0));
}
