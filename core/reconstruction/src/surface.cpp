#include "keyturn/reconstruction/surface.h"

#include <algorithm>
#include <cstring>

#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "open3d_plugin.h"

namespace keyturn::reconstruction {

namespace {

void check(const std::string& error) {
  if (!error.empty()) throw Error(error);
}

template <class T>
void append(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace

OrientedPoints fuseViews(const std::vector<FuseView>& views, const FuseOptions& options) {
  OrientedPoints out;
  check(detail::open3d().fuse_views(views, options, out));
  return out;
}

Mesh poissonSurface(const OrientedPoints& cloud, const PoissonOptions& options) {
  if (cloud.points.size() < 100 || cloud.normals.size() != cloud.points.size())
    throw Error("a Poisson surface needs at least 100 points with normals, got " + std::to_string(cloud.points.size()));
  Mesh out;
  check(detail::open3d().poisson(cloud, options, out));
  return out;
}

Mesh tsdfSurface(const std::vector<DepthFrame>& frames, const OrientedPoints& points, const TsdfOptions& options) {
  if (frames.empty()) throw Error("a TSDF surface needs at least one depth frame");
  if (!(options.voxel_m > 0) || !(options.truncation_m >= options.voxel_m))
    throw Error("a TSDF surface needs a positive voxel and a truncation of at least one voxel");
  for (const auto& f : frames)
    if (f.width <= 0 || f.height <= 0 || f.depth_m.size() != std::size_t(f.width) * std::size_t(f.height) ||
        !(f.fx > 0) || !(f.fy > 0))
      throw Error("a depth frame of " + std::to_string(f.width) + " × " + std::to_string(f.height) + " holds " +
                  std::to_string(f.depth_m.size()) + " depths and needs positive focal lengths");
  Mesh out;
  check(detail::open3d().tsdf(frames, points, options, out));
  return out;
}

Mesh loadMesh(const std::string& path) {
  Mesh out;
  check(detail::open3d().load_mesh(path, out));
  return out;
}

// Little-endian binary PLY (x86 and ARM both are): what CloudCompare, MeshLab and Open3D read.
void saveMeshPly(const std::string& path, const Mesh& mesh) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\ncomment keyturn reconstruct\nelement vertex " +
                      std::to_string(mesh.vertices.size()) + "\nproperty float x\nproperty float y\nproperty float z\n" +
                      "element face " + std::to_string(mesh.triangles.size()) +
                      "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : mesh.vertices) append(bytes, v.x()), append(bytes, v.y()), append(bytes, v.z());
  for (const auto& t : mesh.triangles) {
    append(bytes, std::uint8_t(3));
    append(bytes, std::int32_t(t.x())), append(bytes, std::int32_t(t.y())), append(bytes, std::int32_t(t.z()));
  }
  writeFileDurably(path, bytes);
}

void savePointsPly(const std::string& path, const OrientedPoints& cloud) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\ncomment keyturn reconstruct\nelement vertex " +
                      std::to_string(cloud.points.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
                      "property float nz\nend_header\n";
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    for (int k = 0; k < 3; ++k) append(bytes, cloud.points[i][k]);
    for (int k = 0; k < 3; ++k) append(bytes, cloud.normals[i][k]);
  }
  writeFileDurably(path, bytes);
}

std::vector<double> distancesToMesh(const std::vector<Eigen::Vector3f>& points, const Mesh& reference) {
  std::vector<double> out;
  check(detail::open3d().distances_to_mesh(points, reference, out));
  return out;
}

SurfaceComparison compareSurfaces(const Mesh& surface, const Mesh& reference, double tau_m, std::size_t samples) {
  std::vector<Eigen::Vector3f> s, r;
  check(detail::open3d().sample_mesh(surface, samples, s));
  check(detail::open3d().sample_mesh(reference, samples, r));
  auto within = [&](const std::vector<Eigen::Vector3f>& pts, const Mesh& to) {
    const auto d = distancesToMesh(pts, to);
    return d.empty() ? 0.0 : double(std::count_if(d.begin(), d.end(), [&](double x) { return x <= tau_m; })) / double(d.size());
  };
  SurfaceComparison c;
  c.tau_m = tau_m;
  c.precision = within(s, reference);
  c.recall = within(r, surface);
  c.fscore = c.precision + c.recall > 0 ? 2 * c.precision * c.recall / (c.precision + c.recall) : 0;
  return c;
}

}  // namespace keyturn::reconstruction
