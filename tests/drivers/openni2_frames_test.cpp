// The OpenNI2 camera without a device: the pinhole from a field of view, a depth buffer as an
// organized cloud, and the one-line errors for .oni files that are missing or not recordings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "keyturn/drivers/openni2_camera.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

namespace keyturn {
namespace {

using test::errorOf;

// `--camera openni2` (no URI) with keyturn's simulated camera and a real one both listed: the real one.
TEST(OpenNi2Devices, TheFirstIsARealDeviceBeforeTheSimulatedCamera) {
  EXPECT_EQ(drivers::firstOpenNi2Device({"keyturn-sim://default", "1d27/0601@2/7", "2bc5/0401@1/3"}), "1d27/0601@2/7");
  EXPECT_EQ(drivers::firstOpenNi2Device({"keyturn-sim://default"}), "keyturn-sim://default");
  EXPECT_EQ(drivers::firstOpenNi2Device({}), "");
}

TEST(OpenNi2Intrinsics, FromTheFieldOfViewCentredOnTheImage) {
  // A Kinect v1 / Xtion depth camera: 640 × 480 at fx = fy = 580 px is 57.8° × 45.0°.
  const double hfov = 2 * std::atan(320.0 / 580), vfov = 2 * std::atan(240.0 / 580);
  const DepthIntrinsics k = drivers::intrinsicsFromFieldOfView(hfov, vfov, 640, 480);
  EXPECT_NEAR(k.fx, 580, 1e-9);
  EXPECT_NEAR(k.fy, 580, 1e-9);
  // The middle of 640 pixels numbered 0 … 639 (PCL's OpenNI2 grabber's principal point too).
  EXPECT_DOUBLE_EQ(k.cx, 319.5);
  EXPECT_DOUBLE_EQ(k.cy, 239.5);
  // Half the resolution, half the focal length in pixels.
  EXPECT_NEAR(drivers::intrinsicsFromFieldOfView(hfov, vfov, 320, 240).fx, 290, 1e-9);
  EXPECT_EQ(errorOf([] { drivers::intrinsicsFromFieldOfView(0, 0.5, 640, 480); }),
            "field of view 0.000000° × 28.647890°: each must lie between 0° and 180°");
  EXPECT_NE(errorOf([] { drivers::intrinsicsFromFieldOfView(1, std::nan(""), 640, 480); }), "");
  EXPECT_EQ(errorOf([] { drivers::intrinsicsFromFieldOfView(1, 1, 0, 480); }), "an image of 0 × 480 pixels has no pinhole");
}

TEST(OpenNi2Frames, ADepthBufferBecomesAnOrganizedCloudWithNoReturnAsNaN) {
  // 4 × 3 pixels in rows of 5 (OpenNI2 hands over a stride; the padding must not be read as depth).
  const std::uint32_t w = 4, h = 3, stride_px = 5;
  std::vector<std::uint16_t> buffer(stride_px * h, 0xBEEF);
  const std::uint16_t depth[3][4] = {{1000, 1000, 0, 1000}, {2000, 1500, 1000, 1000}, {1000, 1000, 1000, 4000}};
  for (std::uint32_t v = 0; v < h; ++v) std::memcpy(&buffer[v * stride_px], depth[v], sizeof depth[v]);
  DepthIntrinsics k;
  k.fx = 100;
  k.fy = 200;
  k.cx = 2;
  k.cy = 1;
  const drivers::TofFrame f = drivers::depthCameraFrame(buffer.data(), w, h, stride_px * 2, k, 0.001);
  ASSERT_EQ(f.width, w);
  ASSERT_EQ(f.height, h);
  ASSERT_EQ(f.cloud.width, w);
  ASSERT_EQ(f.cloud.height, h);
  ASSERT_EQ(f.distance.size(), 12u);
  EXPECT_EQ(f.distance[4], 2000);  // row 1 starts after the padding
  EXPECT_EQ(f.distance[11], 4000);
  EXPECT_TRUE(std::isnan(f.cloud.points[2].z()));  // depth 0: no return
  EXPECT_EQ(f.cloud.validCount(), 11u);
  // x = (u − cx) z / fx, y = (v − cy) z / fy, z = depth × unit.
  const Eigen::Vector3f p = f.cloud.points[1 * w + 0];
  EXPECT_FLOAT_EQ(p.z(), 2.0f);
  EXPECT_FLOAT_EQ(p.x(), (0 - 2) * 2.0f / 100);
  EXPECT_FLOAT_EQ(p.y(), 0.0f);
  const Eigen::Vector3f q = f.cloud.points[2 * w + 3];
  EXPECT_FLOAT_EQ(q.z(), 4.0f);
  EXPECT_FLOAT_EQ(q.x(), 1 * 4.0f / 100);
  EXPECT_FLOAT_EQ(q.y(), 1 * 4.0f / 200);
  ASSERT_TRUE(f.depth_camera.has_value());
  EXPECT_EQ(f.depth_camera->depth_unit_m, 0.001);
  EXPECT_EQ(f.depth_camera->intrinsics.fx, 100);
  // 100 µm units: the same numbers, a tenth of the depth.
  EXPECT_FLOAT_EQ(drivers::depthCameraFrame(buffer.data(), w, h, stride_px * 2, k, 0.0001).cloud.points[4].z(), 0.2f);
  EXPECT_EQ(errorOf([&] { drivers::depthCameraFrame(buffer.data(), w, h, 6, k, 0.001); }),
            "depth image: row stride 6 bytes is shorter than 4 pixels");
}

TEST(OpenNi2Recordings, AMissingOrCorruptOniFileIsOneLineNamingIt) {
  const keyturn::test::ScratchFolder scratch("oni");
  const std::filesystem::path& dir = scratch.made();
  drivers::OpenNi2Options o;
  o.oni_file = (dir / "missing.oni").string();
  EXPECT_EQ(errorOf([&] { drivers::OpenNi2Camera camera(o); }), o.oni_file + ": no such .oni recording");
  o.oni_file = (dir / "corrupt.oni").string();
  std::ofstream(o.oni_file) << "not a recording, only words\n";
  const std::string corrupt = errorOf([&] { drivers::OpenNi2Camera camera(o); });
  // Refused by keyturn's check of the container (drivers/oni_recording_check.h) before OpenNI2 reads it.
  EXPECT_EQ(corrupt, o.oni_file + ": not a readable .oni recording (at byte 0: no NI10 file header)");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace keyturn
