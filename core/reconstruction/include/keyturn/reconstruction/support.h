#pragma once
// The support an object stood on while its views were taken (a turntable's platter, a table), in
// the common frame, and the object's foot closed on it. The views' filter removes the support with
// a band above it, and no camera sees the object's underside: without a foot, Poisson closes the
// surface a band's height above the support and bulges under it.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "keyturn/reconstruction/surface.h"

namespace keyturn::reconstruction {

struct SupportView {
  bool found = false;                                 // the filter found and removed a support
  Eigen::Vector4f plane = Eigen::Vector4f::Zero();    // in the view's frame, normal towards the camera
  float band_m = 0;                                   // the height above it removed with it
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();
};

struct Support {
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();  // common frame, unit normal towards the object's side
  double band_m = 0;                                // median over the views
  int views = 0;                                    // views that found it
};

// The median of the views' support planes moved into the common frame, when more than half of the
// views found one and their normals agree (within 10° of the median): none otherwise.
std::optional<Support> commonSupport(const std::vector<SupportView>& views);

// Points on the support under the object's lowest points (those within 1.5 bands + 2 cells of it),
// one per occupied cell of `cell_m` holding at least two of them, with normals facing the support.
OrientedPoints footOnSupport(const OrientedPoints& cloud, const Support& support, double cell_m);

}  // namespace keyturn::reconstruction
