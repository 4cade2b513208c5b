#pragma once
// Fixed-radius neighbourhoods over a PointSet. Organized sets search a pixel
// window sized from the ray spacing (exact, no tree); unorganized sets use
// PCL's FLANN k-d tree.
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

  // Force the k-d tree even for organized sets (benchmarks and cross-checks).
  static std::unique_ptr<RadiusSearch> kdTree(const PointSet& set);

  struct Impl;

 private:
  RadiusSearch() = default;
  std::unique_ptr<Impl> impl_;
};

// Mean distance from each valid point to its nearest neighbour (the "cloud
// resolution" all radii are expressed in). Throws for fewer than 2 points.
double cloudResolution(const PointSet& set);
double cloudResolution(const PointSet& set, const RadiusSearch& search);

}  // namespace keyturn
