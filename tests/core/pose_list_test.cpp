#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"
#include "keyturn/core/pose_list.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
using keyturn::test::errorOf;
namespace fs = std::filesystem;

namespace {
struct PoseFiles : ::testing::Test {
  const test::ScratchFolder scratch{"poses"};
  const fs::path& dir = scratch.made();
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  }
};

// Two views; the second's world ← view turns 90° about z and moves by (0.1, 0.2, 0.3).
const Eigen::Matrix4d kSecond = [] {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.topRightCorner<3, 1>() = Eigen::Vector3d(0.1, 0.2, 0.3);
  return T;
}();
const char* kQ = "0 0 0.7071067811865476 0.7071067811865476";   // +90° about z
const char* kQbar = "0 0 -0.7071067811865476 0.7071067811865476";  // its conjugate
}  // namespace

TEST_F(PoseFiles, EveryFormatGivesTheSamePoses) {
  const std::string keyturn = write("poses.txt", std::string("# view tx ty tz qx qy qz qw\n\n1700000000.1 a.pcd 0 0 0 0 0 0 1\n") +
                                                     "b.pcd 0.1 0.2 0.3 " + kQ + "\n");
  const std::string stanford = write("scans.conf", std::string("camera 0 0 -1 0 0 0 1\nbmesh a.pcd 0 0 0 0 0 0 1\n") +
                                                       "bmesh b.pcd 0.1 0.2 0.3 " + kQbar + "\n");
  const std::string matrix = write("matrices.txt",
                                   "a.pcd 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
                                   "b.pcd 0 -1 0 0.1 1 0 0 0.2 0 0 1 0.3 0 0 0 1\n");
  const std::string tum = write("trajectory.txt", std::string("# timestamp tx ty tz qx qy qz qw\n"
                                                              "100.00 0 0 0 0 0 0 1\n100.50 9 9 9 0 0 0 1\n") +
                                                      "101.00 0.1 0.2 0.3 " + kQ + "\n");
  const std::string stamped = write("depth.txt", "100.01 a.pcd\n100.99 b.pcd\n");
  EXPECT_EQ(detectPoseFormat(keyturn), PoseFormat::Keyturn);
  EXPECT_EQ(detectPoseFormat(stanford), PoseFormat::Stanford);
  EXPECT_EQ(detectPoseFormat(matrix), PoseFormat::Matrix);
  EXPECT_EQ(detectPoseFormat(tum), PoseFormat::Tum);
  PoseReadOptions by_time;
  by_time.views = stamped;
  std::vector<std::vector<PoseListEntry>> all = {readPoses(keyturn), readPoses(stanford), readPoses(matrix),
                                                 readPoses(tum, by_time)};
  for (const auto& poses : all) {
    ASSERT_EQ(poses.size(), 2u);
    EXPECT_EQ(poses[0].file, (dir / "a.pcd").string());
    EXPECT_EQ(poses[1].file, (dir / "b.pcd").string());
    EXPECT_TRUE(poses[0].world_from_view.isIdentity(1e-12));
    EXPECT_TRUE(poses[1].world_from_view.isApprox(kSecond, 1e-9)) << poses[1].world_from_view;
  }
  // TUM by file names that are timestamps, beside the trajectory (the 9 9 9 pose is nobody's).
  write("100.004.pcd", "");
  write("101.000.pcd", "");
  const auto by_name = readPoses(tum);
  ASSERT_EQ(by_name.size(), 2u);
  EXPECT_EQ(fs::path(by_name[0].file).filename(), "100.004.pcd");
  EXPECT_TRUE(by_name[1].world_from_view.isApprox(kSecond, 1e-9));
  // --invert-poses: the other direction.
  PoseReadOptions inverted;
  inverted.invert = true;
  EXPECT_TRUE(readPoses(keyturn, inverted)[1].world_from_view.isApprox(kSecond.inverse(), 1e-9));
}

TEST_F(PoseFiles, TumViewsMustMatchAPose) {
  const std::string tum = write("trajectory.txt", "100.00 0 0 0 0 0 0 1\n101.00 0 0 0 0 0 0 1\n");
  PoseReadOptions o;
  o.views = write("depth.txt", "100.01 a.pcd\n100.50 b.pcd\n");
  EXPECT_NE(errorOf([&] { readPoses(tum, o); }).find("b.pcd: no pose in " + tum + " within 20.0 ms of its timestamp (nearest 0.5"),
            std::string::npos);
  o.views = write("list.txt", "a.pcd\n");
  EXPECT_NE(errorOf([&] { readPoses(tum, o); }).find("list.txt: lists 1 views for the 2 poses of"), std::string::npos);
  EXPECT_NE(errorOf([&] { readPoses(tum); }).find("needs its views: a view list, or TIMESTAMP.pcd/.ply files"), std::string::npos);
}

TEST_F(PoseFiles, MalformedLinesNameFileLineAndWhat) {
  const auto error = [&](const std::string& text, PoseFormat f = PoseFormat::Auto, const std::string& name = "bad.txt") {
    PoseReadOptions o;
    o.format = f;
    return errorOf([&] { readPoses(write(name, text), o); });
  };
  const std::string bad = (dir / "bad.txt").string();
  EXPECT_EQ(error("a.pcd 0 0 0 0 0 0 1\nb.pcd 0 0 x 0 0 0 1\n"), bad + ": line 2: 'x' is not a number");
  EXPECT_EQ(error("a.pcd 0 0 0 0 0 0\n"), bad + ": line 1: expected VIEW_FILE tx ty tz qx qy qz qw, found 7 fields");
  EXPECT_NE(error("a.pcd 0 0 0 0 0 0 2\n").find(bad + ": line 1: quaternion is not unit length (|q| = 2"), std::string::npos);
  EXPECT_EQ(error("camera 0 0 0 0 0 0 1\nmesh a.ply 0 0 0 0 0 0 1\n"), bad + ": line 2: expected a camera or bmesh line, found 'mesh'");
  EXPECT_EQ(error("bmesh a.ply 0 0 0 0 0 1\n"), bad + ": line 1: expected bmesh FILE tx ty tz qx qy qz qw, found 8 fields");
  EXPECT_EQ(error("1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1\n", PoseFormat::Auto, "bad.txt"),
            bad + ": line 2: expected timestamp tx ty tz qx qy qz qw, found 7 fields");
  EXPECT_EQ(error("a.pcd 1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1\n"), bad + ": line 1: last row is not 0 0 0 1");
  EXPECT_EQ(error("a.pcd 2 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"), bad + ": line 1: the upper-left 3 × 3 is not a rotation");
  EXPECT_EQ(error("a.pcd 1 0 0 0 0 1 0 0 0 0 1 0\n", PoseFormat::Matrix),
            bad + ": line 1: expected VIEW_FILE and 16 numbers of a row-major 4 × 4, found 13 fields");
  EXPECT_EQ(error("# nothing\n"), bad + ": no poses listed");
  EXPECT_EQ(error("\v\n\f \n"), bad + ": no poses listed") << "a line of whitespace the tokenizer skips (found by fuzzing)";
  EXPECT_EQ(errorOf([] { parsePoseFormat("ply"); }), "pose format 'ply': expected auto, keyturn, stanford, tum or matrix");
  EXPECT_EQ(errorOf([&] { readPoses((dir / "none.txt").string()); }), (dir / "none.txt").string() + ": no such pose file");
}
