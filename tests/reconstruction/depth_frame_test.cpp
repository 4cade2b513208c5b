// A view as a depth frame for TSDF integration (surface.h's depthFrameFromCloud): the pinhole its
// grid lies on, fitted from the frame, and the filtered points drawn through it. Expected values are
// the intrinsics the synthetic frames were made with.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "keyturn/core/error.h"
#include "keyturn/reconstruction/surface.h"

using namespace keyturn;
using namespace keyturn::reconstruction;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A 64 × 48 frame of a tilted plane through a pinhole (fx 300, fy 310, cx 31.25, cy 24.5), with
// radial distortion k1 applied to each pixel's ray when asked (a grid that is not a pinhole's).
Cloud frame(double k1 = 0) {
  Cloud c;
  c.width = 64, c.height = 48;
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u) {
      double a = (u - 31.25) / 300.0, b = (v - 24.5) / 310.0;
      const double r2 = a * a + b * b;
      a *= 1 + k1 * r2, b *= 1 + k1 * r2;
      const double z = 0.8 + 0.3 * a;  // a plane leaning away to the right
      c.points.emplace_back(float(a * z), float(b * z), float(z));
    }
  c.points[5] = Eigen::Vector3f::Constant(kNaN);  // a pixel with no return
  return c;
}

}  // namespace

TEST(DepthFrame, FitsThePinholeTheGridWasMadeWith) {
  const Cloud c = frame();
  const auto f = depthFrameFromCloud(c, c, Eigen::Matrix4d::Identity());
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->width, 64);
  EXPECT_EQ(f->height, 48);
  EXPECT_NEAR(f->fx, 300.0, 1e-3);
  EXPECT_NEAR(f->fy, 310.0, 1e-3);
  EXPECT_NEAR(f->cx, 31.25, 1e-3);
  EXPECT_NEAR(f->cy, 24.5, 1e-3);
  EXPECT_LT(f->fit_rms_px, 1e-3);
}

TEST(DepthFrame, DrawsTheFilteredPointsAtTheirPixels) {
  const Cloud c = frame();
  Cloud filtered = c;
  for (std::size_t i = 0; i < filtered.size(); ++i)
    if (i % 64 < 32) filtered.points[i] = Eigen::Vector3f::Constant(kNaN);  // the left half filtered out
  const auto f = depthFrameFromCloud(c, filtered, Eigen::Matrix4d::Identity());
  ASSERT_TRUE(f.has_value());
  int drawn = 0;
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u) {
      const float d = f->depth_m[std::size_t(v) * 64 + std::size_t(u)];
      if (u < 32) {
        EXPECT_EQ(d, 0.f) << u << "," << v;  // no measurement where the filter removed the point
      } else {
        EXPECT_NEAR(d, c.points[std::size_t(v) * 64 + std::size_t(u)].z(), 1e-6) << u << "," << v;
        ++drawn;
      }
    }
  EXPECT_EQ(drawn, 32 * 48);
}

TEST(DepthFrame, RefusesWhatIsNotACamerasGrid) {
  std::string why;
  Cloud scan = frame();
  scan.width = std::uint32_t(scan.size()), scan.height = 1;  // the same points, unorganized
  EXPECT_FALSE(depthFrameFromCloud(scan, scan, Eigen::Matrix4d::Identity(), &why).has_value());
  EXPECT_EQ(why, "not an organized depth frame (3072 × 1)");

  const Cloud distorted = frame(-20);  // strong barrel distortion: the corners 6.8 px off the best pinhole, 2.0 px rms
  EXPECT_FALSE(depthFrameFromCloud(distorted, distorted, Eigen::Matrix4d::Identity(), &why).has_value());
  EXPECT_NE(why.find("px rms (a lens model keyturn does not fit)"), std::string::npos) << why;
  // Milder distortion (0.43 px rms) is still a camera's grid.
  const Cloud mild = frame(-5);
  EXPECT_TRUE(depthFrameFromCloud(mild, mild, Eigen::Matrix4d::Identity(), &why).has_value()) << why;

  Cloud empty = frame();
  for (auto& p : empty.points) p = Eigen::Vector3f::Constant(kNaN);
  EXPECT_FALSE(depthFrameFromCloud(empty, empty, Eigen::Matrix4d::Identity(), &why).has_value());
  EXPECT_EQ(why, "0 points in front of the camera, a depth frame needs 100");
}

TEST(DepthFrame, AFrameWhoseDepthsDoNotFillItsGridIsRefusedByTheTsdf) {
  DepthFrame f;
  f.width = 4, f.height = 3, f.fx = f.fy = 100;
  f.depth_m.assign(11, 0.5f);  // one short
  OrientedPoints points;
  try {
    tsdfSurface({f}, points, TsdfOptions());
    FAIL() << "no error";
  } catch (const keyturn::Error& e) {
    EXPECT_STREQ(e.what(), "a depth frame of 4 × 3 holds 11 depths and needs positive focal lengths");
  }
}
