#include "keyturn/reconstruction/support.h"

#include "keyturn/core/median.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

namespace keyturn::reconstruction {

namespace {

// The median of `planes` (unit normals, n·x + d = 0): its normal the component-wise median, its
// offset the median over the planes within `agree_deg` of that normal; none unless more than half of
// the `views` found a plane and that many agree. `agreeing`: how many did.
std::optional<Eigen::Vector4d> medianPlane(const std::vector<Eigen::Vector4d>& planes, std::size_t views,
                                           double agree_deg, int* agreeing = nullptr) {
  if (planes.empty() || 2 * planes.size() <= views) return std::nullopt;
  Eigen::Vector3d m;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> c;
    for (const auto& p : planes) c.push_back(p[k]);
    m[k] = upperMedian(c);
  }
  const Eigen::Vector3d n = m.normalized();
  std::vector<double> offsets;
  for (const auto& p : planes)
    if (p.head<3>().dot(n) > std::cos(agree_deg * M_PI / 180)) offsets.push_back(p[3]);
  if (2 * offsets.size() <= views) return std::nullopt;  // the views disagree on it
  if (agreeing) *agreeing = int(offsets.size());
  return Eigen::Vector4d(n.x(), n.y(), n.z(), upperMedian(offsets));
}

}  // namespace

std::optional<Support> commonSupport(const std::vector<SupportView>& views) {
  std::vector<Eigen::Vector4d> planes;
  std::vector<double> bands;
  for (const auto& v : views) {
    if (!v.found || !(v.plane.head<3>().norm() > 0)) continue;
    // n·x + d = 0 in the view; x = Rᵀ(w − t): (R n)·w + d − (R n)·t = 0.
    const Eigen::Matrix3d R = v.world_from_view.topLeftCorner<3, 3>();
    const Eigen::Vector3d t = v.world_from_view.topRightCorner<3, 1>();
    const Eigen::Vector3d n = (R * v.plane.head<3>().cast<double>()).normalized();
    planes.emplace_back(n.x(), n.y(), n.z(), double(v.plane[3]) / v.plane.head<3>().norm() - n.dot(t));
    bands.push_back(v.band_m);
  }
  Support s;
  const auto plane = medianPlane(planes, views.size(), 10, &s.views);
  if (!plane) return std::nullopt;
  s.plane = *plane;
  s.band_m = upperMedian(bands);
  return s;
}

std::vector<std::optional<Eigen::Vector4d>> rigCameraPlanes(const std::vector<SupportView>& views,
                                                             const std::vector<int>& rig_camera) {
  int cameras = 0;
  for (int k : rig_camera) cameras = std::max(cameras, k + 1);
  std::vector<std::vector<Eigen::Vector4d>> planes(cameras);
  std::vector<std::size_t> count(cameras, 0);
  for (std::size_t i = 0; i < views.size(); ++i) {
    ++count[rig_camera[i]];
    const auto& v = views[i];
    if (!v.found || !(v.plane.head<3>().norm() > 0)) continue;
    Eigen::Vector4d q = v.plane.cast<double>() / double(v.plane.head<3>().norm());
    planes[rig_camera[i]].push_back(q[3] < 0 ? Eigen::Vector4d(-q) : q);  // normal towards the camera
  }
  std::vector<std::optional<Eigen::Vector4d>> out(cameras);
  for (int k = 0; k < cameras; ++k) out[k] = medianPlane(planes[k], count[k], 2);
  return out;
}

RigLevelling levelRigOnSupport(const std::vector<SupportView>& views, const std::vector<int>& rig_camera) {
  const auto planes = rigCameraPlanes(views, rig_camera);
  const int cameras = int(planes.size());
  RigLevelling out;
  for (const auto& v : views) out.world_from_view.push_back(v.world_from_view);
  out.camera_plane.assign(cameras, std::nullopt);
  out.tilt_deg.assign(cameras, 0.0);
  std::vector<int> first(cameras, -1);
  for (std::size_t i = 0; i < views.size(); ++i)
    if (first[rig_camera[i]] < 0) first[rig_camera[i]] = int(i);
  // Where the axis meets each camera's plane in the common frame (through its first view).
  std::vector<double> pivot(cameras, 0), heights;
  std::vector<Eigen::Vector3d> up(cameras);
  for (int k = 0; k < cameras; ++k) {
    const auto& plane = planes[k];
    if (!plane) continue;  // too few views found one, or they disagree: not one platter
    const Eigen::Vector3d n = plane->head<3>();
    const Eigen::Matrix4d& W = views[first[k]].world_from_view;
    const Eigen::Vector3d nw = W.topLeftCorner<3, 3>() * n;
    const double dw = (*plane)[3] - nw.dot(W.topRightCorner<3, 1>());
    if (nw.z() < std::cos(30 * M_PI / 180)) continue;  // not square to the calibrated axis: no platter
    out.camera_plane[k] = *plane;
    up[k] = nw;
    pivot[k] = -dw / nw.z();
    heights.push_back(pivot[k]);
  }
  if (heights.empty()) return out;
  out.height_m = upperMedian(heights);
  for (int k = 0; k < cameras; ++k) {
    if (!out.camera_plane[k]) continue;
    // Turn the plane level about where the axis meets it, then lift it to the common height.
    Eigen::Matrix4d G = Eigen::Matrix4d::Identity();
    G.topLeftCorner<3, 3>() = Eigen::Quaterniond::FromTwoVectors(up[k], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    G.topRightCorner<3, 1>() = Eigen::Vector3d(0, 0, out.height_m) - G.topLeftCorner<3, 3>() * Eigen::Vector3d(0, 0, pivot[k]);
    const Eigen::Matrix4d& W = views[first[k]].world_from_view;
    const Eigen::Matrix4d C = W.inverse() * G * W;
    out.tilt_deg[k] = std::acos(std::clamp(up[k].z(), -1.0, 1.0)) * 180 / M_PI;
    for (std::size_t i = 0; i < views.size(); ++i)
      if (rig_camera[i] == k) out.world_from_view[i] = views[i].world_from_view * C;
  }
  return out;
}

OrientedPoints footOnSupport(const OrientedPoints& cloud, const Support& support, double cell_m) {
  const Eigen::Vector3d n = support.plane.head<3>();
  const Eigen::Vector3d a = (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(n).normalized();
  const Eigen::Vector3d b = n.cross(a);
  const double reach = 1.5 * support.band_m + 2 * cell_m;
  struct Cell {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int count = 0;
  };
  std::map<std::pair<long, long>, Cell> cells;
  for (const auto& pf : cloud.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double h = n.dot(p) + support.plane[3];
    if (h < -cell_m || h > reach) continue;
    const Eigen::Vector2d uv(a.dot(p), b.dot(p));
    Cell& c = cells[{long(std::floor(uv.x() / cell_m)), long(std::floor(uv.y() / cell_m))}];
    c.sum += uv;
    ++c.count;
  }
  OrientedPoints foot;
  const Eigen::Vector3d origin = -support.plane[3] * n;  // the support's point nearest the frame's origin
  for (const auto& [key, c] : cells) {
    if (c.count < 2) continue;  // a stray point of the support's noise is no foot
    const Eigen::Vector2d uv = c.sum / c.count;
    foot.points.push_back((origin + uv.x() * a + uv.y() * b).cast<float>());
    foot.normals.push_back((-n).cast<float>());
  }
  return foot;
}

}  // namespace keyturn::reconstruction
