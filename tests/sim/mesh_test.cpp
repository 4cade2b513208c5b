#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"
#include "keyturn/sim/mesh.h"
#include "keyturn/sim/tof_view.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {
const float kV[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}};
const int kQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

void expectBox(const sim::Mesh& m) {
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_TRUE(m.boundsMin().isApprox(Eigen::Vector3f(0, 0, 0)));
  EXPECT_TRUE(m.boundsMax().isApprox(Eigen::Vector3f(1, 1, 2)));
}

std::string errorOf(const std::string& path) {
  try {
    sim::loadMesh(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Mesh, ObjWithQuadFaces) {
  const keyturn::test::ScratchFolder scratch("mesh");
  const auto p = (scratch.made() / "box.obj").string();
  std::ofstream f(p);
  for (auto& v : kV) f << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << "\n";
  for (auto& q : kQuads) f << "f " << q[0] + 1 << ' ' << q[1] + 1 << ' ' << q[2] + 1 << ' ' << q[3] + 1 << "\n";
  f.close();
  expectBox(sim::loadMesh(p));
}

TEST(Mesh, AsciiStl) {
  const keyturn::test::ScratchFolder scratch("mesh");
  const auto p = (scratch.made() / "box.stl").string();
  std::ofstream f(p);
  f << "solid box\n";
  for (auto& q : kQuads)
    for (int t = 0; t < 2; ++t) {
      const int a = q[0], b = q[t + 1], c = q[t + 2];
      f << " facet normal 0 0 0\n  outer loop\n";
      for (int i : {a, b, c}) f << "   vertex " << kV[i][0] << ' ' << kV[i][1] << ' ' << kV[i][2] << "\n";
      f << "  endloop\n endfacet\n";
    }
  f << "endsolid box\n";
  f.close();
  expectBox(sim::loadMesh(p));
}

TEST(Mesh, BinaryStl) {
  const keyturn::test::ScratchFolder scratch("mesh");
  const auto p = (scratch.made() / "box_bin.stl").string();
  std::string bytes(80, ' ');
  const std::uint32_t n = 12;
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for (auto& q : kQuads)
    for (int t = 0; t < 2; ++t) {
      float rec[12] = {0, 0, 0};
      const int idx[3] = {q[0], q[t + 1], q[t + 2]};
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) rec[3 + 3 * k + c] = kV[idx[k]][c];
      bytes.append(reinterpret_cast<const char*>(rec), sizeof rec);
      bytes.append(2, '\0');  // attribute byte count
    }
  std::ofstream(p, std::ios::binary) << bytes;
  expectBox(sim::loadMesh(p));
  // One byte short: the size no longer matches the count, and it is not "solid" text.
  std::ofstream(p, std::ios::binary) << bytes.substr(0, bytes.size() - 1);
  EXPECT_NE(errorOf(p).find("not a valid STL"), std::string::npos);
}

TEST(Mesh, OffWithComments) {
  const keyturn::test::ScratchFolder scratch("mesh");
  const auto p = (scratch.made() / "box.off").string();
  std::ofstream f(p);
  f << "OFF\n# a 1 x 1 x 2 box\n8 6 0\n";
  for (auto& v : kV) f << v[0] << ' ' << v[1] << ' ' << v[2] << "\n";
  for (auto& q : kQuads) f << "4 " << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << "\n";
  f.close();
  expectBox(sim::loadMesh(p));
}

TEST(Mesh, ShippedPlyLoads) {
  const sim::Mesh m = sim::loadMesh(KEYTURN_DATA_DIR "/objects/mug__ycb_025_mug.ply");
  EXPECT_EQ(m.triangles.size(), 10000u);
  const Eigen::Vector3f size = m.boundsMax() - m.boundsMin();
  EXPECT_NEAR(size.x(), 0.1168f, 1e-3f);  // objects.csv
  EXPECT_NEAR(size.z(), 0.0813f, 1e-3f);
}

TEST(Mesh, BadFilesAreNamedErrors) {
  const keyturn::test::ScratchFolder scratch("mesh");
  const auto off = (scratch.made() / "bad.off").string();
  std::ofstream(off) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  EXPECT_NE(errorOf(off).find("OFF face 0 refers to a missing vertex"), std::string::npos);
  const auto huge = (scratch.made() / "huge.off").string();
  std::ofstream(huge) << "OFF\n2000000000 1 0\n";
  EXPECT_NE(errorOf(huge).find("more than the file can hold"), std::string::npos);
  const auto txt = (scratch.made() / "mesh.3ds").string();
  std::ofstream(txt) << "x";
  EXPECT_NE(errorOf(txt).find("unsupported mesh format '.3ds'"), std::string::npos);
  const auto empty = (scratch.made() / "empty.stl").string();
  std::ofstream(empty).close();
  EXPECT_NE(errorOf(empty).find("empty file"), std::string::npos);
}

// Another instance's size for the same shape: grown about the turntable axis, base still on the table.
TEST(Mesh, ScaledAboutTheTurntableAxisOnTheTable) {
  const sim::Mesh mug = sim::makeMugMesh();
  const sim::Mesh big = sim::scaledMesh(mug, 1.5);
  ASSERT_EQ(big.vertices.size(), mug.vertices.size());
  EXPECT_EQ(big.triangles, mug.triangles);
  EXPECT_NEAR(big.boundsMin().z(), 0.0, 1e-7);
  EXPECT_NEAR(big.boundsMax().z(), 1.5 * mug.boundsMax().z(), 1e-6);
  EXPECT_TRUE((big.boundsMax() - big.boundsMin()).isApprox(1.5f * (mug.boundsMax() - mug.boundsMin()), 1e-6f));
  EXPECT_GT(sim::operatorDistance(big), sim::operatorDistance(mug)) << "framed for its size";
}
