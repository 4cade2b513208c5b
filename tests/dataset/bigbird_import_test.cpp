// keyturn import bigbird on small BigBIRD-layout folders written here (tests/support/bigbird_files.h):
// a view's points in metres from its depth and intrinsics, its pose from poses/ and calibration.h5,
// the mask drawn in the colour camera, the class from --categories, and every bad file one line.
#include <gtest/gtest.h>

#include <algorithm>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "keyturn/core/cloud_io.h"
#include "keyturn/dataset/dataset_import.h"
#include "keyturn/dataset/sidecars.h"
#include "support/bigbird_files.h"
#include "support/scratch_path.h"

using namespace keyturn;
using namespace keyturn::test;
namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t kW = 64, kH = 48;
const FixtureCamera kCam = [] {
  FixtureCamera c;
  c.np = 2;
  c.elevation_deg = 35;
  c.depth_k = {500, 510, 31.5, 23.5};
  c.ir_depth_scale = 1.002;
  return c;
}();

// A wall 8000 units away, one pixel (10, 20) at 7500, and no return in column 40.
std::vector<std::uint16_t> wall() {
  std::vector<std::uint16_t> d(kW * kH, 8000);
  d[20 * kW + 10] = 7500;
  for (std::uint32_t v = 0; v < kH; ++v) d[v * kW + 40] = 0;
  return d;
}

void pose(const fs::path& object, int angle, const Eigen::Matrix4d& table_from_np5) {
  fs::create_directories(object / "poses");
  writeH5((object / "poses" / ("NP5_" + std::to_string(angle) + "_pose.h5")).string(),
          {h5Matrix("H_table_from_reference_camera", table_from_np5)});
}

void view(const fs::path& object, const std::string& stem, const std::vector<H5Dataset>& datasets) {
  fs::create_directories(object);
  writeH5((object / (stem + ".h5")).string(), datasets);
}

dataset::ImportReport run(const fs::path& src, const fs::path& out, const std::string& categories = "") {
  dataset::ImportOptions o;
  o.format = "bigbird";
  o.source = src.string();
  o.out = out.string();
  o.categories = categories;
  return dataset::importDataset(o);
}

}  // namespace

TEST(BigbirdImport, AViewsPointsAreMetresFromItsDepthAndIntrinsicsAndItsPoseFromTheTurntable) {
  const keyturn::test::ScratchFolder scratch("bigbird_view");
  const fs::path& d = scratch.path, obj = d / "src" / "mug_7";
  fs::create_directories(obj);
  writeH5((obj / "calibration.h5").string(), calibrationDatasets({kCam}));
  for (int angle : {0, 3}) {
    pose(obj, angle, cameraFromTable(angle, kNp5ElevationDeg).inverse());
    view(obj, "NP2_" + std::to_string(angle), {h5Depth(wall(), kW, kH)});
  }
  // At 3° a mask: the left half of the colour image (1280 wide) black, the object.
  std::vector<std::uint8_t> left(1280 * 1024, 0);
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = i % 1280 < 640;
  fs::create_directories(obj / "masks");
  writePbm((obj / "masks" / "NP2_3_mask.pbm").string(), left, 1280, 1024);

  const dataset::ImportReport r = run(d / "src", d / "ds");
  EXPECT_TRUE(r.problems.empty()) << r.problems.front();
  EXPECT_EQ(r.imported, 2u);

  const Cloud c = loadCloud((d / "ds/mug_7/mug_7/eNP2/a0.0.pcd").string());
  ASSERT_EQ(c.width, kW);
  ASSERT_EQ(c.height, kH);
  EXPECT_EQ(c.validCount(), std::size_t(kW - 1) * kH);  // column 40 has no return
  const double z = 7500 * 1e-4 * 1.002;                // 100 µm units, NP2_ir_depth_scale
  const Eigen::Vector3f p = c.points[20 * kW + 10];
  EXPECT_NEAR(p.z(), z, 1e-6);
  EXPECT_NEAR(p.x(), (10 - 31.5) * z / 500, 1e-6);
  EXPECT_NEAR(p.y(), (20 - 23.5) * z / 510, 1e-6);
  EXPECT_NEAR(c.points[0].z(), 0.8016, 1e-6);

  // The depth camera ← turntable at each angle: H_NP2_ir_from_NP5 · (H_table_from_NP5)⁻¹.
  for (int angle : {0, 3}) {
    const std::string stem = (d / "ds/mug_7/mug_7/eNP2/a").string() + std::to_string(angle) + ".0";
    const auto m = dataset::readViewTransform(stem + ".json");
    ASSERT_TRUE(m.has_value());
    EXPECT_TRUE(m->isApprox(cameraFromTable(angle, kCam.elevation_deg), 1e-9)) << *m;
  }
  // Its elevation: the table's up (column 2) against the direction from the table to the camera.
  const Eigen::Matrix4d m = cameraFromTable(0, kCam.elevation_deg);
  const Eigen::Vector3d t = m.topRightCorner<3, 1>();
  const double elevation = std::asin(m.block<3, 1>(0, 2).dot(-t) / t.norm()) * 180 / M_PI;
  const auto rows = dataset::Dataset::readManifest((d / "ds").string());
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].key.cls, "mug_7");
  EXPECT_EQ(rows[0].key.elevation, "NP2");
  EXPECT_NEAR(rows[0].elevation_deg, elevation, 1e-3);
  EXPECT_GT(elevation, 36);  // the fixture's board lies off the camera's axis: not the 35° it was turned by

  // The mask keeps the pixels whose points the colour camera (2.5 cm beside the depth one, fx 1050,
  // cx 639.5) sees left of its centre: (u − 31.5) / 500 + 0.025 / z < 0, i.e. u ≤ 15 on the wall,
  // u ≤ 14 for the nearer pixel, which is u = 10: kept too.
  const Cloud masked = loadCloud((d / "ds/mug_7/mug_7/eNP2/a3.0.pcd").string());
  EXPECT_EQ(masked.validCount(), 16u * kH);
  EXPECT_TRUE(Cloud::isValid(masked.points[20 * kW + 10]));
  EXPECT_TRUE(Cloud::isValid(masked.points[5 * kW + 15]));
  EXPECT_FALSE(Cloud::isValid(masked.points[5 * kW + 16]));
}

TEST(BigbirdImport, CategoriesGiveTheClassAndAnObjectNotListedIsOneLine) {
  const keyturn::test::ScratchFolder scratch("bigbird_categories");
  const fs::path& d = scratch.path;
  for (const char* name : {"mug_7", "cup_2"}) {
    const fs::path obj = d / "src" / name;
    fs::create_directories(obj);
    writeH5((obj / "calibration.h5").string(), calibrationDatasets({kCam}));
    pose(obj, 0, cameraFromTable(0, kNp5ElevationDeg).inverse());
    view(obj, "NP2_0", {h5Depth(wall(), kW, kH)});
  }
  std::ofstream(d / "categories.csv") << "class,instance,mesh\nmug,mug_7,\nmug,mug_9,\n";
  const dataset::ImportReport r = run(d / "src", d / "ds", (d / "categories.csv").string());
  EXPECT_EQ(r.imported, 1u);
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0], (d / "src" / "cup_2").string() + ": not in " + (d / "categories.csv").string() +
                               " (no class for instance cup_2) (1 view of cup_2 not imported)");
  EXPECT_TRUE(fs::exists(d / "ds/mug/mug_7/eNP2/a0.0.pcd"));
}

TEST(BigbirdImport, EachBadFileIsOneLineNamingItAndTheRestIsImported) {
  const keyturn::test::ScratchFolder scratch("bigbird_bad");
  const fs::path& d = scratch.path, src = d / "src", good = src / "good";
  fs::create_directories(good);
  writeH5((good / "calibration.h5").string(), calibrationDatasets({kCam}));
  for (int angle = 0; angle <= 15; angle += 3) pose(good, angle, cameraFromTable(angle, kNp5ElevationDeg).inverse());
  view(good, "NP2_0", {h5Depth(wall(), kW, kH)});
  view(good, "NP2_3", {{"depth", H5Type::UInt16, {kW * kH}, std::vector<double>(kW * kH, 8000)}});
  view(good, "NP2_6", {{"depth", H5Type::Int16, {kH, kW}, std::vector<double>(kW * kH, 8000)}});
  view(good, "NP2_9", {h5Matrix("H_table_from_reference_camera", Eigen::Matrix4d::Identity())});
  std::ofstream(good / "NP2_12.h5") << "\x89HDF\r\n\x1a\n" << std::string(300, 'x');
  {  // a good view cut in half
    view(good, "NP2_15", {h5Depth(wall(), kW, kH)});
    fs::resize_file(good / "NP2_15.h5", fs::file_size(good / "NP2_15.h5") / 2);
  }
  view(good, "NP2_18", {h5Depth(wall(), kW, kH)});  // no pose at 18°
  Eigen::Matrix4d sheared = Eigen::Matrix4d::Identity();
  sheared(0, 1) = 0.5;
  pose(good, 21, sheared);
  view(good, "NP2_21", {h5Depth(wall(), kW, kH)});
  std::ofstream(good / "NP6_0.h5") << "";
  std::ofstream(good / "NP2_360.h5") << "";
  std::ofstream(good / "notes.txt") << "taken on a Tuesday\n";
  view(src / "uncalibrated", "NP2_0", {h5Depth(wall(), kW, kH)});
  view(src / "half_calibrated", "NP2_0", {h5Depth(wall(), kW, kH)});
  auto cal = calibrationDatasets({kCam});
  cal.erase(cal.begin());  // NP2_depth_K
  writeH5((src / "half_calibrated" / "calibration.h5").string(), cal);

  const dataset::ImportReport r = run(src, d / "ds");
  EXPECT_EQ(r.imported, 1u);
  const std::string g = good.string() + "/";
  const std::vector<std::string> expected = {
      g + "NP2_360.h5: malformed name (expected NPi_ANGLE.h5, i 1 to 5, ANGLE 0 to 357, or calibration.h5)",
      g + "NP6_0.h5: malformed name (expected NPi_ANGLE.h5, i 1 to 5, ANGLE 0 to 357, or calibration.h5)",
      g + "notes.txt: malformed name (expected NPi_ANGLE.h5, i 1 to 5, ANGLE 0 to 357, or calibration.h5)",
      "missing " + g + "poses/NP5_18_pose.h5 (the turntable's pose at 18°: the views at that angle not imported)",
      g + "poses/NP5_21_pose.h5: dataset \"H_table_from_reference_camera\" is not a rigid transform (the views at 21° not imported)",
      src.string() + "/half_calibrated/calibration.h5: dataset \"NP2_depth_K\" is missing (the NP2 views of half_calibrated not imported)",
      "missing " + src.string() + "/uncalibrated/calibration.h5 (1 view of uncalibrated not imported)",
      g + "NP2_3.h5: dataset \"depth\" is not a two-dimensional image",
      g + "NP2_6.h5: dataset \"depth\" is not 16-bit unsigned (uint16 depth expected)",
      g + "NP2_9.h5: dataset \"depth\" is missing (not a BigBIRD depth image?)",
      g + "NP2_12.h5: corrupt HDF5 file (cannot be opened)",
      g + "NP2_15.h5: corrupt HDF5 file (cannot be opened)",
  };

  std::vector<std::string> got = r.problems;
  EXPECT_EQ(got, expected);
  for (const auto& line : got) EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

TEST(BigbirdImport, ABadMaskIsOneLineAndItsViewNotImported) {
  const keyturn::test::ScratchFolder scratch("bigbird_masks");
  const fs::path& d = scratch.path, obj = d / "src" / "mug_7";
  fs::create_directories(obj / "masks");
  writeH5((obj / "calibration.h5").string(), calibrationDatasets({kCam}));
  std::vector<std::uint8_t> left(1280 * 1024, 0);
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = i % 1280 < 640;
  for (int angle : {0, 3, 6}) {
    pose(obj, angle, cameraFromTable(angle, kNp5ElevationDeg).inverse());
    view(obj, "NP2_" + std::to_string(angle), {h5Depth(wall(), kW, kH)});
    writePbm((obj / "masks" / ("NP2_" + std::to_string(angle) + "_mask.pbm")).string(), left, 1280, 1024);
  }
  const fs::path truncated = obj / "masks" / "NP2_3_mask.pbm", png = obj / "masks" / "NP2_6_mask.pbm";
  fs::resize_file(truncated, fs::file_size(truncated) / 3);
  std::ofstream(png, std::ios::binary) << "\x89PNG\r\n\x1a\n" << std::string(64, '\0');

  const dataset::ImportReport r = run(d / "src", d / "ds");
  EXPECT_EQ(r.imported, 1u);
  ASSERT_EQ(r.problems.size(), 2u);
  std::vector<std::string> got = r.problems;
  std::sort(got.begin(), got.end());
  // Named by the view, then by the mask that failed it.
  EXPECT_EQ(got[0], (obj / "NP2_3.h5").string() + ": " + truncated.string() +
                        ": truncated PBM bitmap");
  EXPECT_EQ(got[1], (obj / "NP2_6.h5").string() + ": " + png.string() + ": not a PBM bitmap (no P4 or P1 magic)");
  for (const auto& line : got) EXPECT_EQ(line.find('\n'), std::string::npos) << line;
  EXPECT_EQ(loadCloud((d / "ds/mug_7/mug_7/eNP2/a0.0.pcd").string()).validCount(), 16u * kH);
}
