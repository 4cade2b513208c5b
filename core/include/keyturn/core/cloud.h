#pragma once
// The point cloud every core algorithm works on. Organized clouds (height > 1)
// keep their pixel grid; removed or invalid pixels hold NaN coordinates.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace keyturn {

struct Cloud {
  std::vector<Eigen::Vector3f> points;  // metres, camera optical frame (x right, y down, z forward)
  std::vector<float> amplitude;         // empty, or one value per point
  std::vector<float> confidence;        // empty, or one value per point
  std::uint32_t width = 0;
  std::uint32_t height = 1;

  bool organized() const { return height > 1; }
  std::size_t size() const { return points.size(); }
  std::size_t validCount() const;
  static bool isValid(const Eigen::Vector3f& p) { return p.allFinite(); }
};

// The valid points of a cloud, compacted. Keeps the pixel of each point when the
// source was organized so neighbourhoods can come from the grid.
struct PointSet {
  std::vector<Eigen::Vector3f> points;
  std::vector<int> pixel;          // pixel index per point, or empty when unorganized
  std::vector<int> pixel_to_point; // -1 where no valid point; empty when unorganized
  std::uint32_t width = 0;
  std::uint32_t height = 1;

  static PointSet fromCloud(const Cloud& cloud);
  // Searched as an unorganized set from now on (its points no longer lie on their pixels' rays).
  void forgetPixels() { pixel.clear(), pixel_to_point.clear(); }
  bool organized() const { return !pixel.empty(); }
  std::size_t size() const { return points.size(); }
  Eigen::Vector3f centroid() const;
};

}  // namespace keyturn
