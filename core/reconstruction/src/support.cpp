#include "keyturn/reconstruction/support.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

namespace keyturn::reconstruction {

namespace {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
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
  if (planes.empty() || 2 * planes.size() <= views.size()) return std::nullopt;
  Support s;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> c;
    for (const auto& p : planes) c.push_back(p[k]);
    s.plane[k] = median(c);
  }
  const Eigen::Vector3d n = s.plane.head<3>().normalized();
  std::vector<double> offsets;
  for (const auto& p : planes)
    if (p.head<3>().dot(n) > std::cos(10 * M_PI / 180)) offsets.push_back(p[3]);
  if (2 * offsets.size() <= views.size()) return std::nullopt;  // the views disagree on it
  s.plane << n, median(offsets);
  s.band_m = median(bands);
  s.views = int(offsets.size());
  return s;
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
