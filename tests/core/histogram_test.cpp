#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "keyturn/core/histogram.h"

using namespace keyturn;

TEST(Histogram, SumsToOneAndBinsCorrectly) {
  const std::vector<float> v = {0.05f, 0.15f, 0.15f, 0.95f, 1.0f};
  int clamped = -1;
  const auto pdf = histogramPdf(v, 10, {0.0, 1.0}, &clamped);
  EXPECT_NEAR(std::accumulate(pdf.begin(), pdf.end(), 0.0), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(pdf[0], 0.2);
  EXPECT_DOUBLE_EQ(pdf[1], 0.4);
  EXPECT_DOUBLE_EQ(pdf[9], 0.4);  // 0.95 and the upper edge 1.0
  EXPECT_EQ(clamped, 0);
}

TEST(Histogram, OutOfRangeIsClampedAndCountedNaNIgnored) {
  int clamped = 0;
  const auto pdf = histogramPdf({-1.f, 5.f, NAN, INFINITY, 0.5f}, 4, {0.0, 1.0}, &clamped);
  EXPECT_EQ(clamped, 2);
  EXPECT_DOUBLE_EQ(pdf[0], 1.0 / 3);
  EXPECT_DOUBLE_EQ(pdf[2], 1.0 / 3);
  EXPECT_DOUBLE_EQ(pdf[3], 1.0 / 3);
}

TEST(Histogram, FarOutliersPastIntRangeAreClamped) {
  // (v - lo) / width * bins is ~1e31 and -1e31 here: bounded before it becomes an int.
  int clamped = 0;
  const auto pdf = histogramPdf({1e30f, -1e30f, 0.3f, 3e38f}, 8, {0.0, 0.5}, &clamped);
  EXPECT_EQ(clamped, 3);
  EXPECT_DOUBLE_EQ(pdf[0], 1.0 / 4);
  EXPECT_DOUBLE_EQ(pdf[4], 1.0 / 4);
  EXPECT_DOUBLE_EQ(pdf[7], 2.0 / 4);
}

TEST(Histogram, EmptyInputGivesZeros) {
  const auto pdf = histogramPdf({}, 8, {0.0, 1.0});
  ASSERT_EQ(pdf.size(), 8u);
  EXPECT_EQ(std::accumulate(pdf.begin(), pdf.end(), 0.0), 0.0);
}
