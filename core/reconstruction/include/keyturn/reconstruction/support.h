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

// Per rig camera, the support plane in that camera's frame (normal towards the camera): the platter
// turns within its own plane, so every view of one camera sees the same plane. The median of its
// views' planes when more than half of them found one and agree within 2°; none otherwise.
std::vector<std::optional<Eigen::Vector4d>> rigCameraPlanes(const std::vector<SupportView>& views,
                                                             const std::vector<int>& rig_camera);

// A turntable's platter is square to its axis, so each rig camera's support plane, the same in all
// of that camera's views, must lie level (normal along the common frame's z, the axis) and at one
// height in the common frame. Per rig camera: the median of its views' planes (in the camera's
// frame) when more than half of its views found one and agree within 2°; the correction that puts it
// level, pivoting where the axis meets it, at the median height of the cameras' planes; applied on the
// right of each of that camera's poses (the camera's pose on the table is what a calibration mis-sets).
struct RigLevelling {
  std::vector<Eigen::Matrix4d> world_from_view;            // the views' poses, levelled
  std::vector<std::optional<Eigen::Vector4d>> camera_plane;  // per rig camera: its plane in the camera's frame
  std::vector<double> tilt_deg;                            // per rig camera: the tilt corrected (0 when not levelled)
  double height_m = 0;                                     // the level planes' height in the common frame
};
RigLevelling levelRigOnSupport(const std::vector<SupportView>& views, const std::vector<int>& rig_camera);

// Points on the support under the object's lowest points (those within 1.5 bands + 2 cells of it),
// one per occupied cell of `cell_m` holding at least two of them, with normals facing the support.
OrientedPoints footOnSupport(const OrientedPoints& cloud, const Support& support, double cell_m);

}  // namespace keyturn::reconstruction
