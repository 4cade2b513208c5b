#pragma once
// The object's surface from registered views: the fused, oriented points and a watertight
// Poisson surface over them (Kazhdan's screened Poisson as Open3D ships it), trimmed where the
// points give it little support (low density: the surface Poisson closes over holes).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"

namespace keyturn::reconstruction {

struct OrientedPoints {
  std::vector<Eigen::Vector3f> points, normals;
};

struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
};

struct FuseOptions {
  double voxel_m = 0.001;  // one point per voxel of the fused cloud
};

// Every view's points in the common frame, one per voxel, with normals facing the sensor: the
// view's origin when it lies outside the view (a camera's frame), else the side a range scan shows
// (its normals' main axis, away from the scan's centroid). Throws keyturn::Error when fewer than
// 100 points remain.
struct FuseView {
  const std::vector<Eigen::Vector3f>* points = nullptr;
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();
};
OrientedPoints fuseViews(const std::vector<FuseView>& views, const FuseOptions& options);

// What is cut from a surface after it is made, whichever way it was made.
struct SurfaceCleanup {
  // > 0: vertices farther than this from every fused point are removed. Poisson closes the surface
  // over what no view saw, and on sparse views bulges far past the object (a simulated SR4000 turn of
  // the scissors: 167 mm wide against the points' 100 mm); the density quantile alone leaves that.
  double max_distance_m = 0;
  // A support the object stood on (ax+by+cz+d=0, normal towards the object's side): vertices more
  // than floor_tolerance_m below it are removed (the surface Poisson closes under the table).
  std::optional<Eigen::Vector4d> floor;
  double floor_tolerance_m = 0.0005;
  std::size_t max_triangles = 0;  // > 0: decimated (quadric error) to at most this many triangles
};

struct PoissonOptions {
  int depth = 9;                 // octree depth (2^depth cells across the object)
  double trim_quantile = 0.03;   // vertices below this density quantile are removed
  SurfaceCleanup cleanup;
};
Mesh poissonSurface(const OrientedPoints& cloud, const PoissonOptions& options);

// One depth frame for TSDF integration: depth along the optical axis in metres per pixel (0: no
// measurement) through a pinhole camera, and where that camera stood in the common frame.
struct DepthFrame {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels
  std::vector<float> depth_m;             // row-major, width × height
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();
  double fit_rms_px = 0;                  // how far the frame's points lie from the fitted pinhole's rays
};

// The pinhole an organized camera-frame view lies on (u = fx·x/z + cx, v = fy·y/z + cy, least
// squares over the frame as read, every valid pixel) and the filtered view's points drawn through
// it (the nearest wins a pixel). Empty, with the reason in *why, when the frame is not organized,
// has fewer than 100 points in front of the camera, or is not a camera's grid (the fit misses its
// pixels by more than 1 px rms: a lens model keyturn does not fit).
std::optional<DepthFrame> depthFrameFromCloud(const Cloud& as_read, const Cloud& filtered,
                                              const Eigen::Matrix4d& world_from_view, std::string* why = nullptr);

// Truncated signed-distance fusion of depth frames (Curless and Levoy; Open3D's
// ScalableTSDFVolume) and its zero set by marching cubes: averages the sensor's noise along each
// ray, and leaves open what no frame saw. `points` (the fused cloud) is what max_distance_m
// measures from.
struct TsdfOptions {
  double voxel_m = 0.001;
  // The signed distance is cut this far on either side of the surface. Too short, and noise leaves
  // holes; too long, and a thin wall's far side erases its near side (the simulated bowl's F-score
  // at 1 mm through the SR4000: 0.81 at 1 mm, 0.72 at 2 mm; the mug's through the OpenNI2 camera,
  // whose noise is 1.5 times the SR4000's: 0.52 at 1.5 mm, 0.80 at 3 mm): about 1.5 σ of the noise.
  double truncation_m = 0.0015;
  SurfaceCleanup cleanup;
};
Mesh tsdfSurface(const std::vector<DepthFrame>& frames, const OrientedPoints& points, const TsdfOptions& options);

// Binary little-endian PLY (vertices and triangles; points and normals); throws keyturn::Error naming the file.
void saveMeshPly(const std::string& path, const Mesh& mesh);
void savePointsPly(const std::string& path, const OrientedPoints& cloud);  // x y z nx ny nz

// A surface against a reference surface (both sampled uniformly, `samples` points each):
// median and 90th-percentile distance of a point set to the reference, and the F-score at tau.
struct SurfaceComparison {
  double precision = 0, recall = 0, fscore = 0;  // at tau
  double tau_m = 0;
};
std::vector<double> distancesToMesh(const std::vector<Eigen::Vector3f>& points, const Mesh& reference);
SurfaceComparison compareSurfaces(const Mesh& surface, const Mesh& reference, double tau_m, std::size_t samples = 200000);

// A triangle mesh file (PLY, OBJ, STL, OFF: Open3D's readers); throws keyturn::Error naming it.
Mesh loadMesh(const std::string& path);

}  // namespace keyturn::reconstruction
