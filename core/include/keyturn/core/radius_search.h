#pragma once
// Fixed-radius neighbourhoods over a PointSet. Organized sets search a pixel
// window sized from the ray spacing (exact, no tree); unorganized sets take their
// nearest distances from a hash grid (nearest_neighbours.h) and use PCL's FLANN
// k-d tree, built on first use, for radius queries the cached table cannot serve.
#include <memory>
#include <vector>

#include "keyturn/core/cloud.h"

namespace keyturn {

class RadiusSearch {
 public:
  explicit RadiusSearch(const PointSet& set);
  ~RadiusSearch();
  RadiusSearch(const RadiusSearch&) = delete;
  RadiusSearch& operator=(const RadiusSearch&) = delete;

  // Indices of points within distance r of point i (strictly less), i included,
  // in ascending index order.
  void radius(int i, float r, std::vector<int>& out) const;
  // Distance from point i to its nearest other point; +inf when it has none.
  float nearestDistance(int i) const;
  bool usesGrid() const;

  // Computes every point's neighbours within `radius` once (a hash grid of that cell
  // size, or the pixel window), so that later queries of any r <= radius are a scan
  // of one short row: ISS's three radii and the graph's all come from one search.
  void cacheNeighbourhoods(float radius);
  float cachedRadius() const { return table_radius_; }

  // Force the k-d tree even for organized sets (benchmarks and cross-checks).
  static std::unique_ptr<RadiusSearch> kdTree(const PointSet& set);

  struct Impl;

 private:
  RadiusSearch() = default;
  std::unique_ptr<Impl> impl_;
  const PointSet* set_ = nullptr;
  float table_radius_ = 0.f;
  std::vector<int> row_offset_;     // size n+1 once cached
  std::vector<int> row_index_;      // neighbours within table_radius_, ascending index per row
  std::vector<float> row_d2_;       // their squared distances
};

// Points farther than this from the origin (metres) are refused: float squared distances
// between them could overflow.
constexpr double kMaxCoordinate = 1e18;

// Mean distance from each valid point to its nearest neighbour (the "cloud
// resolution" all radii are expressed in). Throws keyturn::Error (without a file name) for fewer
// than 2 points and for degenerate sets: coordinates beyond kMaxCoordinate, float coordinates no
// finer than an eighth of the points' spacing (a view stored far from the origin), a resolution of 0
// (every point has a twin).
double cloudResolution(const PointSet& set);
double cloudResolution(const PointSet& set, const RadiusSearch& search);

}  // namespace keyturn
