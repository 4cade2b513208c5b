// The plugin "open3d"'s surfaces (src/open3d_plugin.h): fusing registered views into oriented
// points, Poisson reconstruction, TSDF integration of depth frames, mesh files and distances to a
// mesh, all Open3D's.
#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/TriangleMeshIO.h>
#include <open3d/geometry/BoundingVolume.h>
#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/utility/Logging.h>
#include <open3d/camera/PinholeCameraIntrinsic.h>
#include <open3d/geometry/Image.h>
#include <open3d/geometry/RGBDImage.h>
#include <open3d/pipelines/integration/ScalableTSDFVolume.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "../src/open3d_plugin.h"

namespace keyturn::reconstruction::detail {

namespace o3g = open3d::geometry;

namespace {

std::shared_ptr<o3g::TriangleMesh> toOpen3d(const Mesh& m) {
  auto mesh = std::make_shared<o3g::TriangleMesh>();
  for (const auto& v : m.vertices) mesh->vertices_.push_back(v.cast<double>());
  mesh->triangles_.assign(m.triangles.begin(), m.triangles.end());
  return mesh;
}

Mesh fromOpen3d(const o3g::TriangleMesh& m) {
  Mesh out;
  for (const auto& v : m.vertices_) out.vertices.push_back(v.cast<float>());
  out.triangles.assign(m.triangles_.begin(), m.triangles_.end());
  return out;
}

template <class F>
std::string guarded(F&& f) {
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  try {
    return f();
  } catch (const std::exception& e) {
    return std::string("Open3D: ") + e.what();
  }
}

// The cleanup every surface gets (surface.h's SurfaceCleanup); `points` are the fused points.
void cleanUp(std::shared_ptr<o3g::TriangleMesh>& mesh, const o3g::PointCloud& points, const SurfaceCleanup& options) {
  if (options.max_distance_m > 0 || options.floor) {
    const o3g::KDTreeFlann tree(points);
    std::vector<bool> remove(mesh->vertices_.size(), false);
    std::vector<int> idx(1);
    std::vector<double> d2(1);
    const double reach2 = options.max_distance_m * options.max_distance_m;
    for (std::size_t i = 0; i < mesh->vertices_.size(); ++i) {
      const Eigen::Vector3d& v = mesh->vertices_[i];
      if (options.floor && options.floor->head<3>().dot(v) + (*options.floor)[3] < -options.floor_tolerance_m)
        remove[i] = true;
      else if (options.max_distance_m > 0 && (tree.SearchKNN(v, 1, idx, d2) < 1 || d2[0] > reach2))
        remove[i] = true;
    }
    mesh->RemoveVerticesByMask(remove);
  }
  if (options.max_triangles > 0 && mesh->triangles_.size() > options.max_triangles) {
    mesh = mesh->SimplifyQuadricDecimation(int(options.max_triangles), std::numeric_limits<double>::infinity(), 1.0);
    mesh->RemoveUnreferencedVertices();
  }
}

}  // namespace

std::string fuseEntry(const std::vector<FuseView>& views, const FuseOptions& options, OrientedPoints& out) {
  return guarded([&]() -> std::string {
    o3g::PointCloud all;
    for (const auto& v : views) {
      o3g::PointCloud pc;
      for (const auto& p : *v.points) pc.points_.push_back(p.cast<double>());
      const auto box = pc.GetAxisAlignedBoundingBox();
      const bool sensor_at_origin = !((box.min_bound_.array() <= 0).all() && (box.max_bound_.array() >= 0).all());
      auto down = pc.VoxelDownSample(options.voxel_m);
      down->EstimateNormals(o3g::KDTreeSearchParamHybrid(3 * options.voxel_m, 30));
      if (sensor_at_origin) {
        down->OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
      } else {
        // A scan in a scanner's frame (the Stanford bunny's) does not say where the sensor was,
        // but a range scan shows the surface from one side: its normals cluster about the
        // viewing direction (the normals' main axis), and face away from the scan's centroid.
        Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
        for (const auto& n : down->normals_) scatter += n * n.transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
        down->OrientNormalsToAlignWithDirection(eig.eigenvectors().col(2));
        const Eigen::Vector3d c = down->GetCenter();
        double outward = 0;
        for (std::size_t i = 0; i < down->points_.size(); ++i) outward += down->normals_[i].dot(down->points_[i] - c);
        if (outward < 0)
          for (auto& n : down->normals_) n = -n;
      }
      down->Transform(v.world_from_view);
      all += *down;
    }
    auto fused = all.VoxelDownSample(options.voxel_m);
    if (fused->points_.size() < 100)
      return "the views fuse into " + std::to_string(fused->points_.size()) + " points, a surface needs 100";
    out = {};
    for (std::size_t i = 0; i < fused->points_.size(); ++i) {
      out.points.push_back(fused->points_[i].cast<float>());
      out.normals.push_back(fused->normals_[i].normalized().cast<float>());
    }
    return "";
  });
}

std::string poissonEntry(const OrientedPoints& cloud, const PoissonOptions& options, Mesh& out) {
  return guarded([&]() -> std::string {
    o3g::PointCloud pc;
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      pc.points_.push_back(cloud.points[i].cast<double>());
      pc.normals_.push_back(cloud.normals[i].cast<double>());
    }
    auto [mesh, density] = o3g::TriangleMesh::CreateFromPointCloudPoisson(pc, std::size_t(options.depth), 0, 1.1f,
                                                                           false, -1);
    if (!density.empty() && options.trim_quantile > 0) {
      std::vector<double> sorted = density;
      const std::size_t q = std::min(sorted.size() - 1, std::size_t(options.trim_quantile * double(sorted.size())));
      std::nth_element(sorted.begin(), sorted.begin() + q, sorted.end());
      std::vector<bool> remove(density.size());
      for (std::size_t i = 0; i < density.size(); ++i) remove[i] = density[i] < sorted[q];
      mesh->RemoveVerticesByMask(remove);
    }
    cleanUp(mesh, pc, options.cleanup);
    if (mesh->triangles_.empty()) return "Poisson reconstruction gave no surface";
    out = fromOpen3d(*mesh);
    return "";
  });
}

std::string tsdfEntry(const std::vector<DepthFrame>& frames, const OrientedPoints& points, const TsdfOptions& options,
                      Mesh& out) {
  return guarded([&]() -> std::string {
    namespace integration = open3d::pipelines::integration;
    integration::ScalableTSDFVolume volume(options.voxel_m, options.truncation_m,
                                           integration::TSDFVolumeColorType::NoColor);
    for (const auto& f : frames) {
      o3g::Image depth, color;
      depth.Prepare(f.width, f.height, 1, 4);
      std::memcpy(depth.data_.data(), f.depth_m.data(), f.depth_m.size() * sizeof(float));
      color.Prepare(f.width, f.height, 3, 1);  // unused (NoColor), but the image pair is checked for size
      const o3g::RGBDImage rgbd(color, depth);
      const open3d::camera::PinholeCameraIntrinsic intrinsic(f.width, f.height, f.fx, f.fy, f.cx, f.cy);
      volume.Integrate(rgbd, intrinsic, f.world_from_view.inverse());
    }
    auto mesh = volume.ExtractTriangleMesh();
    mesh->RemoveDuplicatedVertices();
    mesh->RemoveDegenerateTriangles();
    o3g::PointCloud pc;
    for (const auto& p : points.points) pc.points_.push_back(p.cast<double>());
    cleanUp(mesh, pc, options.cleanup);
    if (mesh->triangles_.empty()) return "TSDF integration gave no surface (do the frames' depths overlap?)";
    out = fromOpen3d(*mesh);
    return "";
  });
}

std::string loadMeshEntry(const std::string& path, Mesh& out) {
  return guarded([&]() -> std::string {
    if (!std::filesystem::is_regular_file(path)) return path + ": no such mesh file";
    o3g::TriangleMesh mesh;
    open3d::io::ReadTriangleMeshOptions opt;
    if (!open3d::io::ReadTriangleMesh(path, mesh, opt) || mesh.triangles_.empty())
      return path + ": not a triangle mesh Open3D can read (PLY, OBJ, STL, OFF)";
    out = fromOpen3d(mesh);
    return "";
  });
}

// Point to triangle (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Open3D's RaycastingScene::ComputeDistance would do this exactly, but Debian's libOpen3D 0.16 is
// built with Eigen's assertions on and aborts in it (AlignedVector3::squaredNorm). Here: the
// triangles at the nearest vertices and the nearest triangle centres, each measured exactly.
std::string distancesEntry(const std::vector<Eigen::Vector3f>& points, const Mesh& reference, std::vector<double>& out) {
  return guarded([&]() -> std::string {
    if (reference.triangles.empty()) return "the reference surface has no triangles";
    o3g::PointCloud vertices, centres;
    std::vector<std::vector<int>> incident(reference.vertices.size());
    for (const auto& v : reference.vertices) vertices.points_.push_back(v.cast<double>());
    for (std::size_t t = 0; t < reference.triangles.size(); ++t) {
      const auto& tri = reference.triangles[t];
      centres.points_.push_back((vertices.points_[tri.x()] + vertices.points_[tri.y()] + vertices.points_[tri.z()]) / 3);
      for (int k = 0; k < 3; ++k) incident[tri[k]].push_back(int(t));
    }
    const o3g::KDTreeFlann vtree(vertices), ctree(centres);
    out.assign(points.size(), 0);
#pragma omp parallel for schedule(dynamic, 256)
    for (long i = 0; i < long(points.size()); ++i) {
      const Eigen::Vector3d p = points[i].cast<double>();
      std::vector<int> idx, candidates;
      std::vector<double> d2;
      vtree.SearchKNN(p, 6, idx, d2);
      for (int v : idx) candidates.insert(candidates.end(), incident[v].begin(), incident[v].end());
      ctree.SearchKNN(p, 6, idx, d2);
      candidates.insert(candidates.end(), idx.begin(), idx.end());
      double best = std::numeric_limits<double>::infinity();
      for (int t : candidates) {
        const auto& tri = reference.triangles[t];
        best = std::min(best, (p - closestOnTriangle(p, vertices.points_[tri.x()], vertices.points_[tri.y()],
                                                         vertices.points_[tri.z()])).squaredNorm());
      }
      out[i] = std::sqrt(best);
    }
    return "";
  });
}

std::string sampleEntry(const Mesh& mesh, std::size_t samples, std::vector<Eigen::Vector3f>& out) {
  return guarded([&]() -> std::string {
    const auto pc = toOpen3d(mesh)->SamplePointsUniformly(samples);
    out.clear();
    for (const auto& p : pc->points_) out.push_back(p.cast<float>());
    return "";
  });
}

}  // namespace keyturn::reconstruction::detail
