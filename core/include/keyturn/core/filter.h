#pragma once
// §4.1 filtering of a ToF view: range/box crop, jump-edge removal, dominant
// plane removal (RANSAC), largest-cluster segmentation and statistical outlier
// removal. Each step is optional; the defaults suit an SR4000 at 0.4–1.5 m.
#include <Eigen/Core>

#include "keyturn/core/cloud.h"

namespace keyturn {

struct FilterOptions {
  // Range crop on the distance from the camera (metres); <= 0 disables a bound.
  bool crop_range = true;
  float min_range = 0.1f;
  float max_range = 3.0f;
  // Axis-aligned box crop in the camera frame, off by default.
  bool crop_box = false;
  Eigen::Vector3f box_min{-1.f, -1.f, 0.f};
  Eigen::Vector3f box_max{1.f, 1.f, 3.f};

  // Jump edges (mixed pixels): a pixel with one 8-neighbour nearly straight in
  // front of it and another nearly straight behind it (segments within this
  // angle of its viewing ray) is removed. Organized clouds only.
  bool jump_edge = true;
  float jump_edge_angle_deg = 10.0f;

  // Dominant plane (table/turntable): RANSAC plane whose inliers are removed
  // when they are at least this fraction of the points; points below the plane
  // (on the far side from the camera) are removed with it.
  bool remove_plane = true;
  float plane_distance = 0.008f;
  float plane_min_fraction = 0.15f;
  int plane_iterations = 200;

  // Keep only the largest Euclidean cluster (the object), cluster tolerance in metres.
  bool largest_cluster = true;
  float cluster_tolerance = 0.015f;

  // Statistical outlier removal (PCL): mean k-NN distance beyond mean + std_mul*σ.
  bool outlier_removal = true;
  int sor_k = 12;
  float sor_std_mul = 2.0f;
};

struct FilterReport {
  std::size_t input_valid = 0;
  std::size_t after_crop = 0;
  std::size_t after_jump_edge = 0;
  std::size_t after_plane = 0;
  std::size_t after_cluster = 0;
  std::size_t after_outliers = 0;
  bool plane_found = false;
  Eigen::Vector4f plane{0.f, 0.f, 0.f, 0.f};  // ax+by+cz+d=0, normal towards the camera
};

// Returns a cloud of the same layout (organized stays organized, removed points NaN).
Cloud filterCloud(const Cloud& input, const FilterOptions& options, FilterReport* report = nullptr);

// Individual steps, each keeping the layout.
void cropRange(Cloud& cloud, float min_range, float max_range);
void cropBox(Cloud& cloud, const Eigen::Vector3f& box_min, const Eigen::Vector3f& box_max);
std::size_t removeJumpEdges(Cloud& cloud, float angle_deg);
bool removeDominantPlane(Cloud& cloud, const FilterOptions& options, Eigen::Vector4f* plane);
void keepLargestCluster(Cloud& cloud, float tolerance);
void removeStatisticalOutliers(Cloud& cloud, int k, float std_mul);

}  // namespace keyturn
