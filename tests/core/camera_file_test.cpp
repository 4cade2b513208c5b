// Camera files as users have them (core/camera_file.h): ROS camera_info YAML and CameraInfo
// messages, Open3D's PinholeCameraIntrinsic JSON and OpenCV's FileStorage YAML give the same
// points as keyturn's flat file; distortion is applied (points reproject onto their pixels through
// the forward model); every malformed file is one line naming it and what is wrong.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <opencv2/core.hpp>

#include "keyturn/core/camera_file.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/error.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

void writeText(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary | std::ios::trunc) << s; }

constexpr std::uint32_t kW = 64, kH = 48;

// A slanted surface with a bump, millimetres, a few holes (0 = no return).
fs::path writeDepthImage(const fs::path& d) {
  std::vector<std::uint16_t> depth(kW * kH);
  for (std::uint32_t v = 0; v < kH; ++v)
    for (std::uint32_t u = 0; u < kW; ++u)
      depth[v * kW + u] = (u * 7 + v * 3) % 29 == 0 ? 0 : static_cast<std::uint16_t>(800 + 4 * u + 2 * v + (u - 30) * (v - 20) % 17);
  const fs::path png = d / "view_depth.png";
  savePng16(png.string(), depth, kW, kH);
  return png;
}

// fx 525.5, fy 524.25, cx 31.5, cy 23.75: as each tool writes them.
const char* kFlat = R"({"fx": 525.5, "fy": 524.25, "cx": 31.5, "cy": 23.75})";
const char* kRosCameraInfo = R"(image_width: 64
image_height: 48
camera_name: depth
camera_matrix:
  rows: 3
  cols: 3
  data: [525.5, 0, 31.5, 0, 524.25, 23.75, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0, 0, 0, 0, 0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [525.5, 0, 31.5, 0, 0, 524.25, 23.75, 0, 0, 0, 1, 0]
)";
// `rostopic echo -n 1 /camera/depth/camera_info` (ROS 1; ROS 2 writes k and d).
const char* kCameraInfoMessage = R"(header:
  seq: 42
  stamp:
    secs: 1700000000
    nsecs: 5000
  frame_id: "camera_depth_optical_frame"
height: 48
width: 64
distortion_model: "plumb_bob"
D: [0.0, 0.0, 0.0, 0.0, 0.0]
K: [525.5, 0.0, 31.5, 0.0, 524.25, 23.75, 0.0, 0.0, 1.0]
R: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
P: [525.5, 0.0, 31.5, 0.0, 0.0, 524.25, 23.75, 0.0, 0.0, 0.0, 1.0, 0.0]
binning_x: 0
binning_y: 0
roi:
  x_offset: 0
  y_offset: 0
  height: 0
  width: 0
  do_rectify: False
---
)";
// o3d.io.write_pinhole_camera_intrinsic(PinholeCameraIntrinsic(64, 48, 525.5, 524.25, 31.5, 23.75)), byte for byte.
const char* kOpen3d = "{\n\t\"height\" : 48,\n\t\"intrinsic_matrix\" : [ 525.5, 0.0, 0.0, 0.0, 524.25, 0.0, 31.5, 23.75, 1.0 ],"
                      "\n\t\"width\" : 64\n}";

void writeOpenCv(const fs::path& p, const cv::Mat& d) {
  cv::FileStorage fs(p.string(), cv::FileStorage::WRITE);
  fs << "image_width" << 64 << "image_height" << 48;
  fs << "camera_matrix" << (cv::Mat_<double>(3, 3) << 525.5, 0, 31.5, 0, 524.25, 23.75, 0, 0, 1);
  fs << "distortion_coefficients" << d;
}

void expectSameCloud(const Cloud& a, const Cloud& b, const std::string& what) {
  ASSERT_EQ(a.points.size(), b.points.size()) << what;
  std::size_t valid = 0;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    if (!Cloud::isValid(a.points[i])) {
      EXPECT_FALSE(Cloud::isValid(b.points[i])) << what << " point " << i;
      continue;
    }
    ++valid;
    EXPECT_EQ(a.points[i], b.points[i]) << what << " point " << i;
  }
  EXPECT_GT(valid, kW * kH * 9 / 10) << what;
}

// `text` with its first `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("fixture lacks " + from);
  return text.replace(at, from.size(), to);
}

std::string errorOf(const fs::path& p) {
  try {
    (void)readCameraFile(p.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(CameraFile, RosOpen3dAndOpenCvFilesGiveTheFlatFilesPoints) {
  const keyturn::test::ScratchFolder scratch("camfile");
  const fs::path d = scratch.made();
  const fs::path png = writeDepthImage(d);
  writeText(d / "flat.json", kFlat);
  writeText(d / "ros.yaml", kRosCameraInfo);
  writeText(d / "camera_info.txt", kCameraInfoMessage);
  std::string ros2 = kCameraInfoMessage;  // ROS 2's field names
  ros2 = replaced(ros2, "\nD:", "\nd:");
  ros2 = replaced(ros2, "\nK:", "\nk:");
  writeText(d / "camera_info_ros2.yaml", ros2);
  writeText(d / "open3d.json", kOpen3d);
  writeOpenCv(d / "opencv.yaml", cv::Mat::zeros(1, 5, CV_64F));
  {  // what cv::FileStorage wrote is what the test means to read
    std::ifstream in(d / "opencv.yaml");
    std::string first, all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_EQ(all.rfind("%YAML:1.0\n", 0), 0u) << all;
    ASSERT_NE(all.find("camera_matrix: !!opencv-matrix"), std::string::npos) << all;
  }

  const DepthImageOptions flat = readCameraFile((d / "flat.json").string());
  const Cloud reference = loadCloud(png.string(), flat);
  EXPECT_NEAR(reference.points[kW * 10 + 40].x(), (40 - 31.5) * reference.points[kW * 10 + 40].z() / 525.5, 1e-6);
  for (const char* f : {"ros.yaml", "camera_info.txt", "camera_info_ros2.yaml", "open3d.json", "opencv.yaml"}) {
    const DepthImageOptions o = readCameraFile((d / f).string());
    ASSERT_TRUE(o.intrinsics) << f;
    EXPECT_EQ(o.intrinsics->fx, 525.5) << f;
    EXPECT_EQ(o.intrinsics->fy, 524.25) << f;
    EXPECT_EQ(o.intrinsics->cx, 31.5) << f;
    EXPECT_EQ(o.intrinsics->cy, 23.75) << f;
    EXPECT_TRUE(o.intrinsics->distortion.none()) << f;
    EXPECT_EQ(o.depth_scale, 0.001) << f;
    expectSameCloud(reference, loadCloud(png.string(), o), f);
  }
}

TEST(CameraFile, DistortionIsReadFromEachFormat) {
  const keyturn::test::ScratchFolder scratch("camfile");
  const fs::path d = scratch.made();
  std::string ros = kRosCameraInfo;
  ros = replaced(ros, "data: [0, 0, 0, 0, 0]", "data: [-0.25, 0.08, 0.001, -0.002, 0.01]");
  writeText(d / "ros.yaml", ros);
  std::string message = kCameraInfoMessage;
  message = replaced(message, "D: [0.0, 0.0, 0.0, 0.0, 0.0]", "D: [-0.25, 0.08, 0.001, -0.002, 0.01]");
  writeText(d / "message.yaml", message);
  writeOpenCv(d / "opencv.yaml", (cv::Mat_<double>(1, 5) << -0.25, 0.08, 0.001, -0.002, 0.01));
  writeOpenCv(d / "opencv4.yaml", (cv::Mat_<double>(4, 1) << -0.25, 0.08, 0.001, -0.002));
  writeOpenCv(d / "rational.yaml", (cv::Mat_<double>(1, 8) << -0.25, 0.08, 0.001, -0.002, 0.01, 0.1, 0.02, 0.003));
  for (const char* f : {"ros.yaml", "message.yaml", "opencv.yaml", "opencv4.yaml", "rational.yaml"}) {
    const LensDistortion k = readCameraFile((d / f).string()).intrinsics->distortion;
    EXPECT_EQ(k.k1, -0.25) << f;
    EXPECT_EQ(k.k2, 0.08) << f;
    EXPECT_EQ(k.p1, 0.001) << f;
    EXPECT_EQ(k.p2, -0.002) << f;
    EXPECT_EQ(k.k3, std::string(f) == "opencv4.yaml" ? 0.0 : 0.01) << f;
    EXPECT_EQ(k.k6, std::string(f) == "rational.yaml" ? 0.003 : 0.0) << f;
  }
}

TEST(CameraFile, DistortedPixelsBecomePointsOnTheirDistortedRays) {
  const keyturn::test::ScratchFolder scratch("camfile");
  const fs::path d = scratch.made();
  const fs::path png = writeDepthImage(d);
  writeOpenCv(d / "opencv.yaml", (cv::Mat_<double>(1, 5) << -0.3, 0.12, 0.002, -0.0015, -0.02));
  const DepthImageOptions o = readCameraFile((d / "opencv.yaml").string());
  const DepthIntrinsics& k = *o.intrinsics;
  ASSERT_FALSE(k.distortion.none());
  const Cloud c = loadCloud(png.string(), o);
  // A narrower lens so the corners sit far out: pixel 0 of a 64-wide image at fx 525 is only 0.06
  // off-axis, where this distortion moves a ray by about 1e-4 px. Check with a wide-angle focal length.
  DepthImageOptions wide = o;
  wide.intrinsics->fx = wide.intrinsics->fy = 40;
  const Cloud cw = loadCloud(png.string(), wide);
  double largest_shift = 0;
  for (const auto& [cloud, kk] : {std::pair<const Cloud*, DepthIntrinsics>{&c, k}, {&cw, *wide.intrinsics}})
    for (std::uint32_t v = 0; v < kH; ++v)
      for (std::uint32_t u = 0; u < kW; ++u) {
        const Eigen::Vector3f& p = cloud->points[v * kW + u];
        if (!Cloud::isValid(p)) continue;
        // The forward model takes the point back onto the pixel it was read from.
        const Eigen::Vector2d on_lens = kk.distortion.distort({p.x() / p.z(), p.y() / p.z()});
        EXPECT_NEAR(on_lens.x() * kk.fx + kk.cx, u, 2e-3) << u << "," << v;
        EXPECT_NEAR(on_lens.y() * kk.fy + kk.cy, v, 2e-3) << u << "," << v;
        // …where the plain pinhole would have put it elsewhere.
        largest_shift = std::max(largest_shift, std::hypot(p.x() / p.z() * kk.fx + kk.cx - u, p.y() / p.z() * kk.fy + kk.cy - v));
      }
  EXPECT_GT(largest_shift, 5.0) << "the distortion was not applied";
}

TEST(CameraFile, UndistortionInvertsTheForwardModel) {
  LensDistortion plumb_bob{-0.28, 0.07, 0.0012, -0.0018, 0.0};
  LensDistortion rational{-0.2, 0.05, 0.001, -0.001, 0.01, 0.05, 0.01, 0.002};
  for (const LensDistortion& k : {plumb_bob, rational}) {
    double worst = 0;
    for (double x = -0.6; x <= 0.6; x += 0.05)
      for (double y = -0.45; y <= 0.45; y += 0.05) {
        const Eigen::Vector2d ray(x, y);
        worst = std::max(worst, (k.undistort(k.distort(ray)) - ray).norm());
      }
    EXPECT_LT(worst, 1e-9);
  }
  // Known values: k1 = 0.1 moves (0.5, 0) to 0.5 · (1 + 0.1 · 0.25) = 0.5125.
  EXPECT_DOUBLE_EQ(LensDistortion{0.1}.distort({0.5, 0}).x(), 0.5125);
  EXPECT_NEAR(LensDistortion{0.1}.undistort({0.5125, 0}).x(), 0.5, 1e-12);
  EXPECT_EQ(LensDistortion{}.undistort({0.3, -0.2}), Eigen::Vector2d(0.3, -0.2));
}

TEST(CameraFile, BadFilesAreOneLineNamingTheFileAndTheProblem) {
  const keyturn::test::ScratchFolder scratch("camfile");
  const fs::path d = scratch.made();
  std::string ros8 = kRosCameraInfo;
  ros8 = replaced(ros8, "data: [525.5, 0, 31.5, 0, 524.25, 23.75, 0, 0, 1]", "data: [525.5, 0, 31.5, 0, 524.25, 23.75, 0, 0]");
  std::string ros34 = kRosCameraInfo;
  ros34 = replaced(ros34, "  rows: 3\n  cols: 3\n  data: [525.5", "  rows: 3\n  cols: 4\n  data: [525.5");
  std::string fisheye = kRosCameraInfo;
  fisheye = replaced(fisheye, "plumb_bob", "equidistant");
  fisheye = replaced(fisheye, "cols: 5\n  data: [0, 0, 0, 0, 0]", "cols: 4\n  data: [0.1, 0.01, 0, 0]");
  std::string fisheye_zero = kRosCameraInfo;
  fisheye_zero = replaced(fisheye_zero, "plumb_bob", "equidistant");
  std::string k_short = kCameraInfoMessage;
  k_short = replaced(k_short, "K: [525.5, ", "K: [");
  std::string open3d_row_major = kOpen3d;
  open3d_row_major = replaced(open3d_row_major, "525.5, 0.0, 0.0, 0.0, 524.25, 0.0, 31.5, 23.75, 1.0",
                              "525.5, 0.0, 31.5, 0.0, 524.25, 23.75, 0.0, 0.0, 1.0");
  std::string ros_fx_text = kRosCameraInfo;
  ros_fx_text = replaced(ros_fx_text, "data: [525.5", "data: [fx");
  writeText(d / "nofx.yaml", "fy: 1\ncx: 1\ncy: 1\n");
  writeText(d / "nofx.json", R"({"width": 640, "height": 480})");
  writeText(d / "ros8.yaml", ros8);
  writeText(d / "ros34.yaml", ros34);
  writeText(d / "fisheye.yaml", fisheye);
  writeText(d / "k_short.yaml", k_short);
  writeText(d / "open3d8.json", R"({"width": 64, "height": 48, "intrinsic_matrix": [525.5, 0, 0, 0, 524.25, 0, 31.5, 23.75]})");
  writeText(d / "open3d_row_major.json", open3d_row_major);
  writeText(d / "ros_fx_text.yaml", ros_fx_text);
  writeText(d / "prose.txt", "fx = 525, fy = 525\n");
  writeText(d / "broken.yaml", "camera_matrix: [1, 2\nfx: 3\n");
  writeText(d / "broken.json", R"({"fx": 525, "fy": )");
  writeText(d / "binary.png", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
  writeOpenCv(d / "opencv12.yaml", cv::Mat(1, 12, CV_64F, cv::Scalar(0.01)));
  writeText(d / "empty.yaml", "\n  \n");
  for (const auto& [f, why] : std::vector<std::pair<std::string, std::string>>{
           {"nofx.yaml", "no fx (a camera file holds fx, fy, cx, cy"},
           {"nofx.json", "no fx"},
           {"ros8.yaml", "camera_matrix is 3 × 3 but its data holds 8 values"},
           {"ros34.yaml", "camera_matrix is 3 × 4 but its data holds 9 values"},
           {"fisheye.yaml", "distortion model 'equidistant' with non-zero coefficients: keyturn applies plumb_bob and rational_polynomial only"},
           {"k_short.yaml", "K holds 8 values, a camera matrix has 9 (3 × 3)"},
           {"open3d8.json", "intrinsic_matrix holds 8 values, a camera matrix has 9"},
           {"open3d_row_major.json", "intrinsic_matrix is not a pinhole camera matrix (its last row is not 0 0 1; Open3D stores it column-major"},
           {"ros_fx_text.yaml", "camera_matrix.data[0] is 'fx', not a number"},
           {"prose.txt", "not a camera file: expected JSON or YAML keys"},
           {"broken.yaml", "neither JSON nor valid YAML (line "},
           {"broken.json", "not JSON at byte 18 (unexpected end of input; expected '[', '{', or a literal)"},
           {"binary.png", "a binary file, not a camera file"},
           {"opencv12.yaml", "distortion_coefficients holds 12 values: keyturn applies plumb_bob (k1 k2 p1 p2 [k3]) or rational_polynomial (8)"},
           {"empty.yaml", "empty camera file"},
           {"missing.yaml", "no such file"}}) {
    const std::string msg = errorOf(d / f);
    EXPECT_EQ(msg.rfind((d / f).string() + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(why), std::string::npos) << f << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  writeText(d / "fisheye_zero.yaml", fisheye_zero);  // a model named but nothing to apply
  EXPECT_TRUE(readCameraFile((d / "fisheye_zero.yaml").string()).intrinsics->distortion.none());
}
