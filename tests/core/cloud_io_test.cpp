#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"
#include "support/scratch_path.h"
#include "support/synthetic_clouds.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

Cloud sampleOrganized() {
  Cloud c = test::organizedPlanes(8, 6, 10.f, 1.0f, 0.8f, 2, 5, 1, 4);
  c.points[7].setConstant(std::nanf(""));
  for (std::size_t i = 0; i < c.size(); ++i) {
    c.amplitude.push_back(100.f + i);
    c.confidence.push_back(0.5f + 0.01f * i);
  }
  return c;
}

std::string expectError(const std::string& path) {
  try {
    loadCloud(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}
}  // namespace

class PcdEncodingTest : public ::testing::TestWithParam<PcdEncoding> {};

TEST_P(PcdEncodingTest, RoundTripKeepsOrganizationNaNsAndFields) {
  const keyturn::test::ScratchFolder scratch("io");
  const Cloud c = sampleOrganized();
  const std::string path = (scratch.made() / "rt.pcd").string();
  saveCloud(path, c, GetParam());
  const Cloud r = loadCloud(path);
  ASSERT_EQ(r.width, 8u);
  ASSERT_EQ(r.height, 6u);
  ASSERT_EQ(r.amplitude.size(), c.size());
  ASSERT_EQ(r.confidence.size(), c.size());
  EXPECT_EQ(r.validCount(), c.size() - 1);
  EXPECT_FALSE(Cloud::isValid(r.points[7]));
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (i == 7) continue;
    EXPECT_NEAR((r.points[i] - c.points[i]).norm(), 0.f, 1e-5f) << i;
    EXPECT_NEAR(r.amplitude[i], c.amplitude[i], 1e-3f);
    EXPECT_NEAR(r.confidence[i], c.confidence[i], 1e-5f);
  }
  for (const auto& e : fs::directory_iterator(scratch.made()))
    EXPECT_NE(e.path().filename().string().rfind("rt.pcd.tmp", 0), 0u) << "temporary left: " << e.path();
  // Readable by others like every file keyturn writes (its temporary was made 0600).
  EXPECT_EQ(fs::status(path).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
}

INSTANTIATE_TEST_SUITE_P(AllEncodings, PcdEncodingTest,
                         ::testing::Values(PcdEncoding::Ascii, PcdEncoding::Binary,
                                           PcdEncoding::BinaryCompressed));

TEST(CloudIo, PlyRoundTrip) {
  const keyturn::test::ScratchFolder scratch("io");
  Cloud c = test::unorganized(test::cylinderSurface(0.05f, 0.1f, 12, 4));
  const std::string path = (scratch.made() / "rt.ply").string();
  saveCloud(path, c);
  const Cloud r = loadCloud(path);
  ASSERT_EQ(r.size(), c.size());
  EXPECT_FALSE(r.organized());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR((r.points[i] - c.points[i]).norm(), 0.f, 1e-6f);
}

TEST(CloudIo, MissingFileNamesTheFile) {
  const std::string msg = expectError("/nonexistent/view.pcd");
  EXPECT_NE(msg.find("/nonexistent/view.pcd"), std::string::npos);
  EXPECT_NE(msg.find("no such file"), std::string::npos);
}

TEST(CloudIo, EmptyFile) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "empty.pcd").string();
  std::ofstream(path).close();
  EXPECT_NE(expectError(path).find("empty file"), std::string::npos);
}

TEST(CloudIo, GarbageHeader) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "garbage.pcd").string();
  std::ofstream(path) << "this is not a point cloud\n";
  EXPECT_NE(expectError(path).find("not a valid PCD"), std::string::npos);
}

TEST(CloudIo, BytesOfAFileThatAreNotTextAreEscapedInTheMessage) {
  const keyturn::test::ScratchFolder scratch("io");
  // A PCD beginning with a UTF-16 byte order mark: the message quoted its header bytes raw, which
  // a terminal printed as they were and Python could not decode (keyturn.Error with no message).
  const std::string path = (scratch.made() / "bom.pcd").string();
  std::ofstream(path, std::ios::binary) << "\xff\xfe# .PCD v.7\x1b[31m\nVERSION .7\n";
  EXPECT_EQ(expectError(path), path + ": not a valid PCD file (unknown header line 1: '\\xff\\xfe#')");
  const std::string ply = (scratch.made() / "ctrl.ply").string();
  std::ofstream(ply, std::ios::binary) << "ply\nformat \x1b[2J\xc3\xa9t\xc3 1.0\n";
  EXPECT_EQ(expectError(ply), ply + ": header line 2: unknown format '\\x1b[2J\xc3\xa9t\\xc3'");  // é is kept
}

TEST(CloudIo, PrintableTextKeepsUtf8AndEscapesEveryOtherByte) {
  EXPECT_EQ(printableText("mug × 2 — ok 😀"), "mug × 2 — ok 😀");
  EXPECT_EQ(printableText(std::string("a\0b\tc\n\x7f", 7)), "a\\x00b\\x09c\\x0a\\x7f");
  EXPECT_EQ(printableText("\xc0\xaf"), "\\xc0\\xaf");              // overlong '/'
  EXPECT_EQ(printableText("\xed\xa0\x80"), "\\xed\\xa0\\x80");    // a surrogate
  EXPECT_EQ(printableText("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // past U+10FFFF
  EXPECT_EQ(printableText("\xc2\x9b"), "\\xc2\\x9b");              // C1 control (CSI)
  EXPECT_EQ(printableText("\xe2\x80"), "\\xe2\\x80");              // cut short
}

TEST(CloudIo, TruncatedBinaryAndCompressed) {
  const keyturn::test::ScratchFolder scratch("io");
  for (auto enc : {PcdEncoding::Binary, PcdEncoding::BinaryCompressed}) {
    const std::string path = (scratch.made() / "trunc.pcd").string();
    saveCloud(path, sampleOrganized(), enc);
    // Keep the header and 20 bytes of data (PCL pads files, so cut from the front).
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto data = text.find('\n', text.find("DATA ")) + 1;
    fs::resize_file(path, data + 20);
    EXPECT_NE(expectError(path).find("truncated PCD"), std::string::npos);
  }
}

TEST(CloudIo, UnsupportedExtensionAndDirectory) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "view.xyz").string();
  std::ofstream(path) << "1 2 3\n";
  EXPECT_NE(expectError(path).find("unsupported format"), std::string::npos);
  EXPECT_NE(expectError(scratch.made().string()).find("is a directory"), std::string::npos);
}

TEST(CloudIo, AsciiHeaderPromisingBillionsOfPointsIsRejectedBeforeAllocating) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "huge.pcd").string();
  std::ofstream(path) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                         "WIDTH 2000000000\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2000000000\n"
                         "DATA ascii\n0 0 1\n";
  const std::string msg = expectError(path);
  EXPECT_NE(msg.find("header promises 2000000000 points"), std::string::npos) << msg;
}

TEST(CloudIo, AsciiWithFewerRowsThanPromisedIsAnError) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "short.pcd").string();
  std::ofstream(path) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                         "WIDTH 4\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
                         "0 0 1\n0.1 0 1\n";
  EXPECT_FALSE(expectError(path).empty());
}

TEST(CloudIo, PlyHeaderPromisingMoreVerticesThanTheFileHoldsIsRejected) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "huge.ply").string();
  std::ofstream(path, std::ios::binary) << "ply\nformat binary_little_endian 1.0\n"
                                           "element vertex 2000000000\nproperty float x\n"
                                           "property float y\nproperty float z\nend_header\n";
  EXPECT_NE(expectError(path).find("promises 2000000000"), std::string::npos);
}

TEST(CloudIo, PlyMeshIsRefusedAsAView) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "mesh.ply").string();
  std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                         "0 0 1\n0.1 0 1\n0 0.1 1\n3 0 1 2\n";
  const std::string msg = expectError(path);
  EXPECT_NE(msg.find("mesh.ply: is a mesh (1 faces), not a camera view: render views of it first"), std::string::npos)
      << msg;
}

TEST(CloudIo, PlyWithAnEmptyFaceElementIsACloud) {
  const keyturn::test::ScratchFolder scratch("io");
  const std::string path = (scratch.made() / "noface.ply").string();
  std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
                         "0 0 1\n0.1 0 1\n";
  EXPECT_EQ(loadCloud(path).size(), 2u);
}
