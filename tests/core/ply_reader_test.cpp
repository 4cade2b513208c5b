// keyturn's own PLY reader: formats, types, lists, organized clouds and the
// errors a malformed file must produce.
#include "keyturn/core/ply_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "keyturn/core/cloud_io.h"
#include "support/error_of.h"
#include "support/synthetic_clouds.h"
#include "support/scratch_path.h"

using namespace keyturn;
namespace fs = std::filesystem;

namespace {

std::string write(const fs::path& dir, const std::string& name, const std::string& bytes) {
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

template <typename T>
std::string bytesOf(T v, bool big_endian) {
  std::string s(sizeof v, '\0');
  std::memcpy(s.data(), &v, sizeof v);
  if (big_endian) std::reverse(s.begin(), s.end());
  return s;
}

const char* kMeshHeader =
    "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

std::string binaryTriangle(bool big) {
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment made by a test\n" + kMeshHeader;
  const double xyz[9] = {0, 0, 0, 1.5, 0, 0, 0, -2.25, 0.125};
  for (double v : xyz) s += bytesOf(v, big);
  s += bytesOf(std::uint8_t{3}, big);
  for (std::int32_t i : {0, 1, 2}) s += bytesOf(i, big);
  return s;
}

}  // namespace

class PlyByteOrder : public ::testing::TestWithParam<bool> {};

TEST_P(PlyByteOrder, ReadsDoublesAndAFaceList) {
  const keyturn::test::ScratchFolder scratch("ply_reader");
  const PlyData ply = readPly(write(scratch.made(), "tri.ply", binaryTriangle(GetParam())));
  const PlyElement* v = ply.find("vertex");
  ASSERT_NE(v, nullptr);
  ASSERT_EQ(v->count, 3u);
  EXPECT_DOUBLE_EQ(v->find("x")->values[1], 1.5);
  EXPECT_DOUBLE_EQ(v->find("y")->values[2], -2.25);
  EXPECT_DOUBLE_EQ(v->find("z")->values[2], 0.125);
  const PlyProperty* idx = ply.find("face")->find("vertex_indices");
  ASSERT_TRUE(idx->is_list);
  EXPECT_EQ(idx->offsets, (std::vector<std::size_t>{0, 3}));
  EXPECT_EQ(idx->values, (std::vector<double>{0, 1, 2}));
}

INSTANTIATE_TEST_SUITE_P(LittleAndBig, PlyByteOrder, ::testing::Values(false, true));

TEST(PlyReader, AsciiWithCrLfAndNegativeIntegers) {
  const keyturn::test::ScratchFolder scratch("ply_reader");
  const PlyData ply = readPly(write(scratch.made(), "a.ply",
                                    "ply\r\nformat ascii 1.0\r\nelement vertex 2\r\nproperty float x\r\n"
                                    "property short y\r\nproperty uchar z\r\nend_header\r\n0.5 -7 255\r\n1e-3 3 0\r\n"));
  const PlyElement* v = ply.find("vertex");
  EXPECT_FLOAT_EQ(static_cast<float>(v->find("x")->values[1]), 1e-3f);
  EXPECT_EQ(v->find("y")->values[0], -7);
  EXPECT_EQ(v->find("z")->values[0], 255);
}

TEST(PlyReader, OrganizedCloudWrittenByKeyturnKeepsItsGrid) {
  const keyturn::test::ScratchFolder scratch("ply_reader");
  Cloud c = test::organizedPlanes(16, 12, 50.f, 1.0f, 0.8f, 4, 9, 3, 7);
  c.amplitude.assign(c.size(), 0.25f);
  ASSERT_TRUE(c.organized());
  const std::string path = write(scratch.made(), "org.ply", "");
  saveCloud(path, c);
  const Cloud r = loadCloud(path);
  EXPECT_EQ(r.width, c.width);
  EXPECT_EQ(r.height, c.height);
  ASSERT_EQ(r.size(), c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.points[i].allFinite()) EXPECT_NEAR((r.points[i] - c.points[i]).norm(), 0.f, 1e-6f);
}

TEST(PlyReader, AGridWhoseSidesMultiplyToTheCountOnlyModulo2To64IsIgnored) {
  const keyturn::test::ScratchFolder scratch("ply_reader");
  // 8589934605 × 545761658833005647 = 3 (mod 2^64): multiplied, the check passed and the
  // cloud became a 13 × 1321528399 "grid" (the sides cut to 32 bits) over 3 points.
  const std::string path = write(scratch.made(), "grid.ply",
                                 "ply\nformat ascii 1.0\nobj_info num_cols 8589934605\nobj_info num_rows 545761658833005647\n"
                                 "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
                                 "0 0 1\n0 1 1\n1 0 1\n");
  const Cloud c = loadCloud(path);
  EXPECT_EQ(c.width, 3u);
  EXPECT_EQ(c.height, 1u);
  ASSERT_EQ(c.size(), 3u);
}

TEST(PlyReader, MalformedFilesAreOneClearLine) {
  const keyturn::test::ScratchFolder scratch("ply_reader");
  struct Case {
    const char* name;
    std::string bytes;
    const char* expected;
  };
  const std::string tri = binaryTriangle(false);
  const Case cases[] = {
      {"nomagic.ply", "format ascii 1.0\n", "must start with 'ply'"},
      {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", "no end_header"},
      {"fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown format"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n1\n",
       "unknown property type 'quad'"},
      {"orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", "a property before any element"},
      {"cut.ply", tri.substr(0, tri.size() - 5), "the data ends inside element 'face' item 0"},
      {"word.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\nabc\n",
       "bad number 'abc'"},
      {"frac.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\nend_header\n1 2.5\n",
       "non-integer '2.5'"},
      {"neglist.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list int int v\nend_header\n-4 1\n",
       "bad list length -4"},
      {"huge.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n",
       "promises 99999999999 items"},
      // List lengths past any integer type: named as written, never cast (was UB in the message).
      {"hugelist.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\nend_header\n66666666666666666666666 1\n",
       "bad list length 6.666666667e+22 in element 'face' item 0"},
      {"inflist.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\nend_header\ninf 1\n",
       "bad list length inf"},
      {"bigbin.ply", "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uint int v\nend_header\n" +
                         bytesOf<std::uint32_t>(4000000000u, false) + std::string(8, '\0'),
       "bad list length 4000000000"},
      // A token is a number only as a whole: strtod stops at a NUL byte, and a 64-character
      // cap must not split a long one in two.
      {"nul.ply", std::string("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1") + std::string(2, '\0') + "\n",
       "bad number '1\\x00\\x00'"},
      {"long.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n" + std::string(70, '6') + "\n",
       "a number longer than 64 characters ('66666666666666666666...')"},
  };
  for (const auto& c : cases) {
    const std::string path = write(scratch.made(), c.name, c.bytes);
    const std::string msg = test::errorOf([&] { readPly(path); });
    EXPECT_NE(msg.find(path + ": "), std::string::npos) << c.name << ": " << msg;
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.name << ": " << msg;
  }
}
