// Depth images as views: the pinhole arithmetic, masks and crop offsets (Washington RGB-D's
// companions), camera files, every bad file one line naming it, and a real Kinect frame projected
// to a depth PNG and read back.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/camera_file.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/error.h"
#include "keyturn/core/view_files.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

void writeText(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary | std::ios::trunc) << s; }

void writeMask(const fs::path& p, int w, int h, const std::vector<std::uint8_t>& on) {
  cv::Mat m(h, w, CV_8UC1);
  for (int i = 0; i < w * h; ++i) m.data[i] = on[static_cast<std::size_t>(i)] ? 255 : 0;
  ASSERT_TRUE(cv::imwrite(p.string(), m));
}

std::string errorOf(const std::string& path, const DepthImageOptions& o) {
  try {
    (void)loadCloud(path, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

DepthImageOptions withIntrinsics(double fx, double fy, double cx, double cy) {
  DepthImageOptions o;
  o.intrinsics = DepthIntrinsics{fx, fy, cx, cy};
  return o;
}

}  // namespace

TEST(DepthImage, PixelsBecomePinholePoints) {
  // 3 × 2: (2, 1) holds 1500 units; (0, 0) no return; (1, 0) masked out.
  const std::vector<std::uint16_t> depth = {0, 800, 900, 1000, 1200, 1500};
  const std::vector<std::uint8_t> mask = {1, 0, 1, 1, 1, 1};
  const Cloud c = depthImageToCloud(depth, 3, 2, {500, 400, 1, 0.5}, 0.001, mask, {10, 20});
  ASSERT_EQ(c.width, 3u);
  ASSERT_EQ(c.height, 2u);
  EXPECT_FALSE(Cloud::isValid(c.points[0]));
  EXPECT_FALSE(Cloud::isValid(c.points[1]));
  EXPECT_EQ(c.validCount(), 4u);
  // x = (2 + 10 − 1) · 1.5 / 500, y = (1 + 20 − 0.5) · 1.5 / 400.
  EXPECT_NEAR(c.points[5].x(), 0.033, 1e-7);
  EXPECT_NEAR(c.points[5].y(), 0.076875, 1e-7);
  EXPECT_NEAR(c.points[5].z(), 1.5, 1e-7);
  EXPECT_NEAR(c.points[2].x(), (2 + 10 - 1) * 0.9 / 500, 1e-7);
  EXPECT_NEAR(c.points[2].y(), (0 + 20 - 0.5) * 0.9 / 400, 1e-7);
}

TEST(DepthImage, WashingtonCompanionsGiveTheMaskAndTheCropOffset) {
  const keyturn::test::ScratchFolder scratch("depth");
  const fs::path d = scratch.made();
  const std::vector<std::uint16_t> depth = {700, 710, 720, 730, 740, 750};
  savePng16((d / "mug_1_1_5_depthcrop.png").string(), depth, 3, 2);
  writeMask(d / "mug_1_1_5_maskcrop.png", 3, 2, {0, 1, 1, 1, 1, 0});
  writeText(d / "mug_1_1_5_loc.txt", "301,221\n");  // 1-based, as Washington's MATLAB writes it

  const Cloud c = loadCloud((d / "mug_1_1_5_depthcrop.png").string(), withIntrinsics(570.3, 570.3, 319, 239));
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c.validCount(), 4u);  // the mask's two zeros
  EXPECT_FALSE(Cloud::isValid(c.points[0]));
  EXPECT_FALSE(Cloud::isValid(c.points[5]));
  // Pixel (1, 0) is (301, 220) 0-based in the full frame.
  EXPECT_NEAR(c.points[1].x(), (1 + 300 - 319) * 0.71 / 570.3, 1e-7);
  EXPECT_NEAR(c.points[1].y(), (0 + 220 - 239) * 0.71 / 570.3, 1e-7);
  EXPECT_NEAR(c.points[1].z(), 0.71, 1e-7);

  // Given options win over the companions.
  DepthImageOptions o = withIntrinsics(570.3, 570.3, 319, 239);
  o.crop = CropOffset{0, 0};
  o.depth_scale = 0.0001;
  const Cloud c2 = loadCloud((d / "mug_1_1_5_depthcrop.png").string(), o);
  EXPECT_NEAR(c2.points[1].x(), (1 - 319) * 0.071 / 570.3, 1e-7);
}

TEST(DepthImage, FoldersListDepthImagesOnlyWhenAskedAndNeverTheirCompanions) {
  const keyturn::test::ScratchFolder scratch("depth");
  const fs::path d = scratch.made();
  savePng16((d / "v1_depth.png").string(), {1, 2, 3, 4}, 2, 2);
  writeMask(d / "v1_mask.png", 2, 2, {1, 1, 1, 1});
  savePng16((d / "a0.0_distance.png").string(), {1, 2, 3, 4}, 2, 2);
  writeText(d / "a0.0.pcd", "x");
  EXPECT_EQ(collectViewFiles({d.string()}).files, std::vector<std::string>{(d / "a0.0.pcd").string()});
  EXPECT_EQ(collectViewFiles({d.string()}, true).files,
            (std::vector<std::string>{(d / "a0.0.pcd").string(), (d / "v1_depth.png").string()}));
}

TEST(DepthImage, CameraFilesInJsonAndYaml) {
  const keyturn::test::ScratchFolder scratch("depth");
  const fs::path d = scratch.made();
  writeText(d / "cam.json", R"({"fx": 525.5, "fy": 524.0, "cx": 319.5, "cy": 239.5, "depth_scale": 0.0002, "name": "x"})");
  writeText(d / "cam.yaml", "%YAML:1.0\n# a Kinect\nfx: 525.5\nfy: 524.0   # px\ncx: 319.5\ncy: \"239.5\"\n");
  for (const char* f : {"cam.json", "cam.yaml"}) {
    const DepthImageOptions o = readCameraFile((d / f).string());
    ASSERT_TRUE(o.intrinsics) << f;
    EXPECT_DOUBLE_EQ(o.intrinsics->fx, 525.5);
    EXPECT_DOUBLE_EQ(o.intrinsics->fy, 524.0);
    EXPECT_DOUBLE_EQ(o.intrinsics->cx, 319.5);
    EXPECT_DOUBLE_EQ(o.intrinsics->cy, 239.5);
  }
  EXPECT_DOUBLE_EQ(readCameraFile((d / "cam.json").string()).depth_scale, 0.0002);
  EXPECT_DOUBLE_EQ(readCameraFile((d / "cam.yaml").string()).depth_scale, 0.001);

  writeText(d / "nocy.yaml", "fx: 1\nfy: 1\ncx: 1\n");
  writeText(d / "bad.yaml", "fx: 1\nfy: one\ncx: 1\ncy: 1\n");
  writeText(d / "bad.json", "{\"fx\": 1,");
  writeText(d / "neg.json", R"({"fx": -1, "fy": 1, "cx": 1, "cy": 1})");
  for (const auto& [f, why] : {std::pair<std::string, std::string>{"nocy.yaml", "no cy"},
                               {"bad.yaml", "fy is 'one', not a number"},
                               {"bad.json", "not JSON at byte 9 (unexpected end of input; expected string literal)"},
                               {"neg.json", "fx and fy must be positive"},
                               {"none.json", "no such file"}}) {
    const std::string file = (d / f).string();
    try {
      (void)readCameraFile(file);
      ADD_FAILURE() << f << " accepted";
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << msg;
      EXPECT_NE(msg.find(why), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
}

TEST(DepthImage, BadImagesAreOneLineNamingTheFile) {
  const keyturn::test::ScratchFolder scratch("depth");
  const fs::path d = scratch.made();
  const DepthImageOptions o = withIntrinsics(500, 500, 1, 1);
  savePng16((d / "good.png").string(), {100, 200, 300, 400}, 2, 2);
  cv::Mat eight(2, 2, CV_8UC1, cv::Scalar(9));
  ASSERT_TRUE(cv::imwrite((d / "eight.png").string(), eight));
  cv::Mat colour(2, 2, CV_16UC3, cv::Scalar(9, 9, 9));
  ASSERT_TRUE(cv::imwrite((d / "colour.png").string(), colour));
  writeText(d / "empty.png", "");
  std::ifstream in(d / "good.png", std::ios::binary);
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  writeText(d / "truncated.png", good.substr(0, good.size() / 2));
  std::string scrambled = good;
  for (std::size_t i = 40; i + 16 < scrambled.size(); ++i) scrambled[i] = static_cast<char>(scrambled[i] ^ 0x5a);
  writeText(d / "scrambled.png", scrambled);
  writeText(d / "text.png", "not an image at all\n");
  savePng16((d / "v_depth.png").string(), {100, 200, 300, 400}, 2, 2);
  writeMask(d / "v_mask.png", 3, 2, {1, 1, 1, 1, 1, 1});

  EXPECT_EQ(loadCloud((d / "good.png").string(), o).validCount(), 4u);
  const std::pair<std::string, std::string> cases[] = {
      {"eight.png", "8-bit image"},
      {"colour.png", "3-channel image"},
      {"empty.png", "empty file"},
      {"truncated.png", "truncated PNG"},
      {"scrambled.png", "corrupt PNG"},
      {"text.png", "not a PNG file"},
      {"v_mask.png", "mask is 3 × 2, its depth image"},
  };
  for (const auto& [f, why] : cases) {
    const std::string file = (d / f).string();
    const std::string msg = errorOf(f == "v_mask.png" ? (d / "v_depth.png").string() : file, o);
    EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << f << ": " << msg;
    EXPECT_NE(msg.find(why), std::string::npos) << f << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  const std::string no_k = errorOf((d / "good.png").string(), {});
  EXPECT_EQ(no_k.rfind((d / "good.png").string() + ": a depth image needs the camera's intrinsics", 0), 0u) << no_k;
}

// A depth image and the PCD made from it are the same view: equal PDFs, equal K.
TEST(DepthImage, DescribesToTheSamePdfsAsThePcdMadeFromIt) {
  const keyturn::test::ScratchFolder scratch("depth");
  const fs::path d = scratch.made();
  // A box on a table seen from 0.8 m, 160 × 120, millimetres.
  const std::uint32_t w = 160, h = 120;
  std::vector<std::uint16_t> depth(w * h);
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      const bool box = u > 55 && u < 105 && v > 35 && v < 85;
      depth[v * w + u] = static_cast<std::uint16_t>(box ? 740 + ((u * 7 + v * 3) % 11) : 800 + v / 4);
    }
  savePng16((d / "view.png").string(), depth, w, h);
  const DepthImageOptions o = withIntrinsics(140, 140, 79.5, 59.5);
  saveCloud((d / "view.pcd").string(), loadCloud((d / "view.png").string(), o));
  const ViewDescriptor a = describeView(loadCloud((d / "view.png").string(), o), DescriptorOptions());
  const ViewDescriptor b = describeView(loadCloud((d / "view.pcd").string()), DescriptorOptions());
  ASSERT_GT(a.keypointCount(), 4);
  EXPECT_EQ(a.keypointCount(), b.keypointCount());
  ASSERT_EQ(a.pdfs.size(), b.pdfs.size());
  for (std::size_t i = 0; i < a.pdfs.size(); ++i) EXPECT_EQ(a.pdfs[i], b.pdfs[i]) << i;
}

#ifdef KEYTURN_REAL_DATA
// A real Kinect frame (mOSD learn0, 640 × 480) projected to a millimetre depth PNG with the
// intrinsics its grid implies, and read back: the same pixels valid, every point within the
// quantisation of its depth.
TEST(DepthImage, ARealKinectFrameSurvivesADepthPng) {
  const keyturn::test::ScratchFolder scratch("depth");
  const Cloud original = loadCloud(std::string(KEYTURN_REAL_DATA) + "/full/learn0.pcd");
  ASSERT_EQ(original.width, 640u);
  // u = fx · x/z + cx (and v likewise) by least squares over the valid pixels.
  Eigen::Matrix2d au = Eigen::Matrix2d::Zero(), av = Eigen::Matrix2d::Zero();
  Eigen::Vector2d bu = Eigen::Vector2d::Zero(), bv = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < original.size(); ++i) {
    const Eigen::Vector3f& p = original.points[i];
    if (!Cloud::isValid(p) || p.z() <= 0) continue;
    const double u = static_cast<double>(i % original.width), v = static_cast<double>(i / original.width);
    const Eigen::Vector2d xu(p.x() / p.z(), 1), xv(p.y() / p.z(), 1);
    au += xu * xu.transpose(), bu += xu * u, av += xv * xv.transpose(), bv += xv * v;
  }
  const Eigen::Vector2d ku = au.ldlt().solve(bu), kv = av.ldlt().solve(bv);
  EXPECT_NEAR(ku[0], 525, 30);  // a Kinect's focal length in pixels
  std::vector<std::uint16_t> depth(original.size(), 0);
  for (std::size_t i = 0; i < original.size(); ++i)
    if (Cloud::isValid(original.points[i])) depth[i] = static_cast<std::uint16_t>(std::lround(original.points[i].z() * 1000));
  const fs::path png = scratch.made() / "learn0_depth.png";
  savePng16(png.string(), depth, original.width, original.height);

  const Cloud back = loadCloud(png.string(), withIntrinsics(ku[0], kv[0], ku[1], kv[1]));
  ASSERT_EQ(back.size(), original.size());
  ASSERT_EQ(back.validCount(), original.validCount());
  double worst_z = 0, worst_xy = 0;
  for (std::size_t i = 0; i < original.size(); ++i) {
    if (!Cloud::isValid(original.points[i])) continue;
    ASSERT_TRUE(Cloud::isValid(back.points[i])) << i;
    worst_z = std::max(worst_z, static_cast<double>(std::abs(back.points[i].z() - original.points[i].z())));
    worst_xy = std::max(worst_xy, static_cast<double>((back.points[i] - original.points[i]).head<2>().norm()));
  }
  EXPECT_LE(worst_z, 0.0005 + 1e-6);  // half a millimetre: the PNG's unit
  EXPECT_LE(worst_xy, 0.001);
  std::printf("mOSD learn0: fx %.2f fy %.2f cx %.2f cy %.2f; worst |dz| %.3f mm, |dxy| %.3f mm\n", ku[0], kv[0], ku[1],
              kv[1], 1000 * worst_z, 1000 * worst_xy);
}
#endif
