// A wrong depth scale (core/depth_scale_check.h): Open3D's units per metre (1000, 10000) given as
// keyturn's metres per unit is caught with the scale that fits; a right scale, or a scene that is
// merely far away, is left alone.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <tuple>

#include "keyturn/core/depth_image.h"
#include "keyturn/core/depth_scale_check.h"
#include "keyturn/core/error.h"

using namespace keyturn;

namespace {

// 30 × 20 pixels of raw depth `units` (±5 % across the image), read with `scale` metres per unit.
Cloud frame(double units, double scale) {
  std::vector<std::uint16_t> depth(30 * 20);
  for (std::size_t i = 0; i < depth.size(); ++i) depth[i] = static_cast<std::uint16_t>(units * (0.95 + 0.1 * (i % 30) / 30.0));
  depth[7] = 0;  // a hole
  return depthImageToCloud(depth, 30, 20, {525, 525, 14.5, 9.5}, scale);
}

// The error checkDepthScale throws, or nothing.
std::optional<DepthScaleError> caught(const Cloud& c, double scale, const FilterOptions& f = {}) {
  try {
    checkDepthScale("view_depth.png", c, scale, f);
  } catch (const DepthScaleError& e) {
    return e;
  }
  return std::nullopt;
}

}  // namespace

TEST(DepthScaleCheck, UnitsPerMetreGivenAsMetresPerUnitIsCaughtWithItsReciprocal) {
  // Millimetres (1,000 per metre) at about 1 m read with 1000, and TUM-like 10,000 per metre with 10000.
  for (const auto& [units, scale, suggested] : {std::tuple{1000.0, 1000.0, 0.001}, std::tuple{10000.0, 10000.0, 0.0001}}) {
    const auto e = caught(frame(units, scale), scale);
    ASSERT_TRUE(e) << scale;
    EXPECT_DOUBLE_EQ(e->scale, scale);
    EXPECT_NEAR(e->suggested_scale, suggested, 1e-15);
    EXPECT_TRUE(e->reciprocal());
    EXPECT_NEAR(e->median_m, units * scale * 1.0, units * scale * 0.06);
    EXPECT_NEAR(e->suggested_median_m, 1.0, 0.06);
    EXPECT_EQ(e->in_range, 0u);
    EXPECT_EQ(e->valid, 599u);
    const std::string msg = e->what();
    EXPECT_EQ(msg.rfind("view_depth.png: depth scale ", 0), 0u) << msg;
    EXPECT_NE(msg.find(" (1/" + std::string(scale == 1000 ? "1000" : "10000") + ") would put it at 1.0 m"), std::string::npos) << msg;
    EXPECT_NE(msg.find("0 of 599 points within the 0.1–3 m"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("--"), std::string::npos) << msg;  // no flag words in core
  }
}

TEST(DepthScaleCheck, MillimetresReadAsMetresGetThePowerOfTenThatFits) {
  const auto e = caught(frame(1500, 1.0), 1.0);  // 1,500 "m"
  ASSERT_TRUE(e);
  EXPECT_DOUBLE_EQ(e->suggested_scale, 0.001);
  EXPECT_FALSE(e->reciprocal());
  EXPECT_NE(std::string(e->what()).find("puts the median distance at 1,5"), std::string::npos) << e->what();
}

TEST(DepthScaleCheck, RightScalesAndFarScenesAreLeftAlone) {
  EXPECT_FALSE(caught(frame(1000, 0.001), 0.001));     // millimetres, 1 m
  EXPECT_FALSE(caught(frame(10000, 0.0001), 0.0001));  // 10,000 per metre, 1 m
  EXPECT_FALSE(caught(frame(4000, 0.001), 0.001));     // 4 m: beyond the crop, but a scene, not a scale
  FilterOptions off;
  off.crop_range = false;
  EXPECT_FALSE(caught(frame(1000, 1000), 1000, off));  // nothing is cropped by range
  Cloud few_in_range = frame(1000, 1000);              // 2 % of the points in range: not "almost nothing"
  for (int i = 0; i < 12; ++i) few_in_range.points[40 + i] = Eigen::Vector3f(0, 0, 1);
  EXPECT_FALSE(caught(few_in_range, 1000));
  for (int i = 0; i < 7; ++i) few_in_range.points[40 + i] = Eigen::Vector3f(0, 0, 2e6f);  // 5 left: < 1 %
  EXPECT_TRUE(caught(few_in_range, 1000));
}

TEST(DepthScaleCheck, MetresAreWrittenForPeople) {
  EXPECT_EQ(formatMetres(1e6), "1,000,000 m");
  EXPECT_EQ(formatMetres(1000), "1,000 m");
  EXPECT_EQ(formatMetres(1.04), "1.0 m");
  EXPECT_EQ(formatMetres(0.05), "0.05 m");
}
