#pragma once
// Triangle meshes for the simulated scene (metres, z up, base on z = 0).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace keyturn::sim {

struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;

  Eigen::Vector3f boundsMin() const;
  Eigen::Vector3f boundsMax() const;
};

// PLY (ascii or binary, float or double vertices) through PCL, STL through
// PCL's VTK reader (after keyturn checks its size), OBJ and OFF by keyturn's own
// small parsers (PCL's OBJ reader crashed on fuzzed input). Polygons are
// fan-triangulated. Throws keyturn::Error naming the file for a missing,
// unreadable, truncated or face-less mesh.
Mesh loadMesh(const std::string& path);

// A built-in mug (cylindrical wall with a bottom and a torus-section handle),
// 8 cm wide and 10 cm tall, so a view can be rendered with no file at all.
Mesh makeMugMesh();

// The axis-calibration target: a sphere of `radius` resting on the table at
// `offset` from the turntable axis (+x at 0°).
Mesh makeSphereTargetMesh(double radius = 0.03, double offset = 0.07);

// "builtin:mug", "builtin:sphere-target", or a mesh file.
Mesh loadMeshOrBuiltin(const std::string& name);

// The mesh grown by `factor` about the origin (the turntable axis on the table), so its base stays
// on z = 0 and it stays centred on the table: another instance's size for the same shape.
Mesh scaledMesh(Mesh mesh, double factor);

}  // namespace keyturn::sim
