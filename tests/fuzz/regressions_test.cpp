// Inputs the fuzzers found to crash or exhaust memory, kept as regression tests:
// each must now be one clear keyturn::Error.
#include <gtest/gtest.h>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/sim/mesh.h"
#include "support/error_of.h"

using keyturn::test::errorOf;

TEST(FuzzRegression, PcdWithAGarbledFieldsLineIsRejectedBeforePcl) {
  // Crashed PCL's PCDReader::read (SEGV): SIZE/TYPE/COUNT present, FIELDS not.
  const std::string msg = errorOf([] { keyturn::loadCloud(KEYTURN_REGRESSIONS "/pcd_garbled_fields_line.pcd"); });
  EXPECT_NE(msg.find("pcd_garbled_fields_line.pcd: not a valid PCD file (unknown header line 3: 'LxFDIES')"), std::string::npos)
      << msg;
}

TEST(FuzzRegression, StlThatLooksBinaryWithAHugeCountIsRejectedBeforeVtk) {
  // Made VTK's STL reader allocate 6.6 GB: one non-ASCII byte, a huge count at bytes 80–83.
  // keyturn reads STL itself now; this file has "solid" text with a stray byte in a vertex line.
  const std::string msg = errorOf([] { keyturn::sim::loadMesh(KEYTURN_REGRESSIONS "/stl_false_binary_huge_count.stl"); });
  EXPECT_NE(msg.find("stl_false_binary_huge_count.stl: a facet ends with"), std::string::npos) << msg;
}

TEST(FuzzRegression, PcdWithUnknownHeaderLinesIsRejectedBeforePcl) {
  // Crashed PCL's PCDReader::read (SEGV): extra lines before VERSION throw off its line count.
  const std::string msg = errorOf([] { keyturn::loadCloud(KEYTURN_REGRESSIONS "/pcd_unknown_header_lines.pcd"); });
  EXPECT_NE(msg.find("unknown header line 2: 'property'"), std::string::npos) << msg;
}

TEST(FuzzRegression, ObjVertexWithAMissingCoordinateIsNamed) {
  // Crashed PCL's OBJReader (SEGV in its number parsing): "v 0 00".
  const std::string msg = errorOf([] { keyturn::sim::loadMesh(KEYTURN_REGRESSIONS "/obj_vertex_missing_coordinate.obj"); });
  EXPECT_NE(msg.find("obj_vertex_missing_coordinate.obj: line 1: a vertex needs x y z"), std::string::npos) << msg;
}

TEST(FuzzRegression, PlyCloudThatCrashedPclsVertexCallbackIsReadWithinItsBytes) {
  // Crashed PCL's PLYReader::vertexScalarPropertyCallback<float> (SEGV): an organized-cloud
  // header (2 × 3 grid) over 11 vertices plus a range_grid list. keyturn's own reader reads
  // the 11 vertices and, as the grid does not match, leaves the cloud unorganized.
  const auto cloud = keyturn::loadCloud(KEYTURN_REGRESSIONS "/ply_cloud_crash_in_pcl_vertex_callback.ply");
  EXPECT_EQ(cloud.points.size(), 11u);
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_EQ(cloud.amplitude.size(), 11u);
}

TEST(FuzzRegression, PlyMeshWithAGarbledPropertyLineIsNamed) {
  // Crashed PCL's PLYReader::vertexListPropertyContentCallback<int> (SEGV).
  const std::string msg = errorOf([] { keyturn::sim::loadMesh(KEYTURN_REGRESSIONS "/ply_mesh_crash_in_pcl_list_callback.ply"); });
  EXPECT_NE(msg.find("ply_mesh_crash_in_pcl_list_callback.ply: header line 5: unknown keyword 'prorfte'"),
            std::string::npos)
      << msg;
}

TEST(FuzzRegression, PlyMeshWithAHugeAsciiListLengthIsNamedWithoutACast) {
  // UBSan, fuzz_mesh after 533,140 runs: "6.66667e+22 is outside the range of representable
  // values of type 'long long'" in the message for a bad list length. That length came from
  // two more faults in the ASCII reader: an 86-byte run of digits and NUL bytes was cut into
  // 64-byte tokens, and strtod stopped at the NULs, so "6666…\0\0\0\0666…" read as two numbers.
  // The run is one token now, refused as too long; the list-length path itself is tested in
  // PlyReader.MalformedFilesAreOneClearLine (hugelist.ply, inflist.ply).
  const std::string msg = errorOf([] { keyturn::sim::loadMesh(KEYTURN_REGRESSIONS "/ply_mesh_huge_list_length.ply"); });
  EXPECT_NE(msg.find("ply_mesh_huge_list_length.ply: a number longer than 64 characters ('66666666666666666666...') "
                     "in element 'vertex' item 0"),
            std::string::npos)
      << msg;
}

TEST(FuzzRegression, PcdWithASecondDataLineIsRejectedBeforePcl) {
  // fuzz_point_cloud, 300 s pass (issue 35): PCL's PCDReader::readHeader reads on after DATA and
  // indexed the bare second "DATA" line's missing type: std::out_of_range escaped loadCloud.
  const std::string msg = errorOf([] { keyturn::loadCloud(KEYTURN_REGRESSIONS "/pcd_second_data_line.pcd"); });
  EXPECT_NE(msg.find("pcd_second_data_line.pcd: corrupt PCD header: line 10 ('DATA') is a header line after DATA "
                     "(line 9)"),
            std::string::npos)
      << msg;
}

// Clouds that load fine and are geometrically degenerate (issue 35): each crashed the chain with
// SIGSEGV in RadiusSearch::radius (a zero resolution left the neighbour table unbuilt, then read).
TEST(ChainRegression, OnePointCopiedAThousandTimesIsOneLine) {
  const keyturn::Cloud c = keyturn::loadCloud(KEYTURN_REGRESSIONS "/chain_one_point_1000_times.pcd");
  const std::string msg = errorOf([&] { keyturn::describeView(c, keyturn::DescriptorOptions()); });
  EXPECT_EQ(msg, "degenerate cloud: its 1000 points lie on only 1 distinct position, every one shared "
                 "(nearest-neighbour distance 0, so no resolution)");
}

TEST(ChainRegression, ASphereFarFromTheOriginIsOneLineNamingFloatPrecision) {
  // A 5 cm sphere of 3,000 points 1,000 km from the origin: stored as float, its coordinates are
  // 6.25 cm apart there, so the sphere is a handful of lattice points.
  const keyturn::Cloud c = keyturn::loadCloud(KEYTURN_REGRESSIONS "/chain_sphere_5cm_1000km.pcd");
  const std::string msg = errorOf([&] { keyturn::describeView(c, keyturn::DescriptorOptions()); });
  EXPECT_NE(msg.find("degenerate cloud: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("5.77e+05 m from the origin, where float coordinates are 0.0625 m apart"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(ChainRegression, PointsFartherThanFloatDistancesReachAreInvalid) {
  // fuzz_chain, first 300 s pass: points up to 1e38 m out survived the cluster step (far cells
  // share a voxel) and reached the working resolution, where every squared distance to a voxel's
  // mean was inf, no point became the voxel's representative and cloud.points[-1] was read (UBSan:
  // pointer overflow; ASan: heap-buffer-overflow). Points beyond kMaxCoordinate are invalid now,
  // in the filter as in the loaders, so the near cluster is what is described.
  keyturn::Cloud c;
  for (int i = 0; i < 100; ++i) c.points.emplace_back(1e37f * static_cast<float>(1 + i % 10), 0.f, 1.f);
  for (int i = 0; i < 60; ++i)
    c.points.emplace_back(0.01f * static_cast<float>(i % 4), 0.01f * static_cast<float>((i / 4) % 4), 1.f + 0.01f * static_cast<float>(i / 16));
  c.width = static_cast<std::uint32_t>(c.points.size());
  // The points the chain describes: some, and every one within the near cluster's box
  // (0..0.03, 0..0.03, 1..1.03 m; voxel means stay inside it).
  const keyturn::PreparedView prepared = keyturn::prepareView(c, keyturn::DescriptorOptions());
  ASSERT_GT(prepared.points.size(), 0u);
  for (const auto& p : prepared.points.points) {
    EXPECT_TRUE(p.x() > -1e-4f && p.x() < 0.0301f && p.y() > -1e-4f && p.y() < 0.0301f && p.z() > 0.9999f &&
                p.z() < 1.0301f)
        << p.transpose();
  }
  // Described, they reach ISS and no other error: a lattice of 4 × 4 × 4 cm has too few keypoints, the
  // one error left.
  const std::string msg = errorOf([&] { keyturn::describeView(c, keyturn::DescriptorOptions()); });
  EXPECT_EQ(msg, "too few keypoints: ISS found 1 in " + std::to_string(prepared.points.size()) +
                     " points (need at least 3; move the camera closer or lower the radii)");
}
