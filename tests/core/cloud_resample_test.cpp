#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "keyturn/core/cloud_resample.h"
#include "keyturn/core/error.h"

using namespace keyturn;

namespace {
// A 640 × 480 frame whose pixel (u, v) holds the point (u, v, 1 + u % 7), NaN on a
// block, with amplitude = pixel index: every resampled pixel can be traced back.
Cloud tracedFrame() {
  Cloud c;
  c.width = 640;
  c.height = 480;
  for (int v = 0; v < 480; ++v)
    for (int u = 0; u < 640; ++u) {
      const bool hole = u >= 100 && u < 200 && v >= 50 && v < 150;
      c.points.push_back(hole ? Eigen::Vector3f::Constant(NAN) : Eigen::Vector3f(u, v, 1.f + u % 7));
      c.amplitude.push_back(static_cast<float>(v * 640 + u));
    }
  return c;
}
}  // namespace

TEST(ResampleOrganized, KeepsAspectAndHitsTheRequestedPixelCount) {
  const Cloud f = tracedFrame();
  // The sizes `keyturn bench --scaling` asks for, and the grids they give.
  const std::tuple<std::size_t, unsigned, unsigned> cases[] = {
      {1000, 37, 27}, {3000, 63, 47}, {10000, 115, 87}, {30000, 200, 150}, {100000, 365, 274}};
  for (const auto& [n, w, h] : cases) {
    const Cloud r = resampleOrganized(f, n);
    EXPECT_EQ(r.width, w) << n;
    EXPECT_EQ(r.height, h) << n;
    ASSERT_EQ(r.size(), std::size_t(w) * h) << n;
    EXPECT_NEAR(double(r.size()) / n, 1.0, 0.02) << n;
    EXPECT_TRUE(r.organized());
  }
}

TEST(ResampleOrganized, EveryPixelIsTheNearestSourcePixelsMeasurement) {
  const Cloud f = tracedFrame();
  const Cloud r = resampleOrganized(f, 30000);  // 200 × 150: every 3.2 source pixels
  ASSERT_EQ(r.amplitude.size(), r.size());
  for (unsigned v = 0; v < r.height; ++v)
    for (unsigned u = 0; u < r.width; ++u) {
      const std::size_t i = v * r.width + u;
      const int src = static_cast<int>(r.amplitude[i]);
      const int su = src % 640, sv = src / 640;
      // The source pixel contains the output pixel's centre.
      EXPECT_LE(std::abs((u + 0.5) * 3.2 - (su + 0.5)), 0.5 + 1e-9);
      EXPECT_LE(std::abs((v + 0.5) * 3.2 - (sv + 0.5)), 0.5 + 1e-9);
      if (Cloud::isValid(f.points[src]))
        EXPECT_EQ(r.points[i], f.points[src]);  // copied, never averaged
      else
        EXPECT_FALSE(Cloud::isValid(r.points[i]));  // holes stay holes
    }
  EXPECT_EQ(r.points[0], Eigen::Vector3f(1, 1, 2));  // centre 1.6 → pixel 1
}

TEST(ResampleOrganized, FullSizeIsTheFrameAndBadInputThrows) {
  const Cloud f = tracedFrame();
  const Cloud same = resampleOrganized(f, 307200);
  EXPECT_EQ(same.width, 640u);
  EXPECT_EQ(same.points.size(), f.points.size());
  Cloud flat;
  flat.points = {Eigen::Vector3f(0, 0, 1)};
  flat.width = 1;
  EXPECT_THROW(resampleOrganized(flat, 1), Error);
  EXPECT_THROW(resampleOrganized(f, 0), Error);
}

TEST(RandomSubset, DistinctValidPointsAndRepeatable) {
  const Cloud f = tracedFrame();
  const Cloud a = randomSubset(f, 3000, 7);
  ASSERT_EQ(a.size(), 3000u);
  EXPECT_FALSE(a.organized());
  EXPECT_EQ(a.width, 3000u);
  std::set<int> seen;
  int left_half = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(Cloud::isValid(a.points[i]));
    const int src = static_cast<int>(a.amplitude[i]);
    EXPECT_EQ(a.points[i], f.points[src]);
    EXPECT_TRUE(seen.insert(src).second) << "drawn twice: " << src;
    if (i > 0) {
      EXPECT_GT(src, static_cast<int>(a.amplitude[i - 1]));  // source order
    }
    if (src % 640 < 320) ++left_half;
  }
  // Uniform over the 297,200 valid pixels, 143,600 of them in the left half: 1450 expected, σ ≈ 27.
  EXPECT_NEAR(left_half, 3000.0 * 143600 / 297200, 5 * 27.4);
  const Cloud b = randomSubset(f, 3000, 7);
  EXPECT_EQ(b.amplitude, a.amplitude);
  const Cloud c = randomSubset(f, 3000, 8);
  EXPECT_NE(c.amplitude, a.amplitude);
  EXPECT_THROW(randomSubset(f, 297201, 7), Error);
  EXPECT_EQ(randomSubset(f, 297200, 7).size(), 297200u);
}
