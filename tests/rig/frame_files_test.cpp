// A frame on disk: the organized PCD reads back as the frame's cloud, the PNGs beside it.
#include "keyturn/rig/frame_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "keyturn/core/cloud_io.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
namespace fs = std::filesystem;

namespace {

drivers::TofFrame frame() {
  drivers::TofFrame f;
  f.width = 4;
  f.height = 3;
  for (std::uint32_t i = 0; i < f.width * f.height; ++i) {
    f.distance.push_back(static_cast<std::uint16_t>(1000 * i));
    f.amplitude.push_back(static_cast<std::uint16_t>(i + 7));
    f.confidence.push_back(0xFFFF);
  }
  f.cloud.width = f.width;
  f.cloud.height = f.height;
  for (std::uint32_t i = 0; i < f.width * f.height; ++i)
    f.cloud.points.push_back(i == 5 ? Eigen::Vector3f::Constant(std::nanf("")) : Eigen::Vector3f(0.01f * i, -0.02f * i, 0.5f + 0.001f * i));
  f.cloud.amplitude.assign(f.amplitude.begin(), f.amplitude.end());
  f.cloud.confidence.assign(f.cloud.points.size(), 1.0f);
  return f;
}

}  // namespace

TEST(FrameFiles, ThePcdReadsBackAsTheFrameAndThePngsLieBesideIt) {
  const keyturn::test::ScratchFolder scratch("frame_files");
  const std::filesystem::path& d = scratch.path;
  const drivers::TofFrame f = frame();
  const auto written = rig::writeFrameFiles((d / "view.pcd").string(), f);
  ASSERT_EQ(written.size(), 4u);
  for (const char* name : {"view.pcd", "view_distance.png", "view_amplitude.png", "view_confidence.png"})
    EXPECT_TRUE(fs::is_regular_file(d / name)) << name;
  for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos);
  const Cloud back = loadCloud((d / "view.pcd").string());
  ASSERT_EQ(back.width, 4u);
  ASSERT_EQ(back.height, 3u);
  EXPECT_EQ(back.validCount(), 11u);
  EXPECT_TRUE(std::isnan(back.points[5].x()));
  EXPECT_FLOAT_EQ(back.points[7].y(), -0.14f);
  ASSERT_EQ(back.amplitude.size(), 12u);
  EXPECT_FLOAT_EQ(back.amplitude[3], 10.f);
}

TEST(FrameFiles, AViewNotNamedPcdIsRefused) {
  const keyturn::test::ScratchFolder scratch("frame_files_bad");
  const std::filesystem::path& d = scratch.path;
  const std::string e = test::errorOf([&] { rig::writeFrameFiles((d / "view.ply").string(), frame()); });
  EXPECT_NE(e.find("view.ply: the view must be written as a .pcd file"), std::string::npos) << e;
}
