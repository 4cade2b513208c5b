#include "keyturn/core/axis_calibration.h"

#include <Eigen/Dense>
#include <cmath>

#include "keyturn/core/error.h"

namespace keyturn {

SphereFit fitSphere(const std::vector<Eigen::Vector3f>& pts) {
  const int n = static_cast<int>(pts.size());
  if (n < 4) throw Error("sphere fit needs at least 4 points, got " + std::to_string(n));
  // |p|² = 2 c·p + (r² − |c|²): linear in (c, k).
  Eigen::MatrixXd A(n, 4);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = pts[i].cast<double>();
    A.row(i) << 2 * p.x(), 2 * p.y(), 2 * p.z(), 1.0;
    b[i] = p.squaredNorm();
  }
  const Eigen::Vector4d s = A.colPivHouseholderQr().solve(b);
  SphereFit f;
  f.centre = s.head<3>();
  const double r2 = s[3] + f.centre.squaredNorm();
  if (!(r2 > 0) || !std::isfinite(r2)) throw Error("sphere fit: degenerate points (coplanar or collinear?)");
  f.radius = std::sqrt(r2);
  // Gauss–Newton on the geometric residual |p − c| − r.
  for (int it = 0; it < 10; ++it) {
    Eigen::MatrixXd J(n, 4);
    Eigen::VectorXd res(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d d = pts[i].cast<double>() - f.centre;
      const double len = std::max(d.norm(), 1e-12);
      res[i] = len - f.radius;
      J.row(i) << -d.x() / len, -d.y() / len, -d.z() / len, -1.0;
    }
    const Eigen::Vector4d step = (J.transpose() * J).ldlt().solve(-J.transpose() * res);
    f.centre += step.head<3>();
    f.radius += step[3];
    if (step.norm() < 1e-10) break;
  }
  double ss = 0;
  for (const auto& p : pts) {
    const double r = (p.cast<double>() - f.centre).norm() - f.radius;
    ss += r * r;
  }
  f.rms = std::sqrt(ss / n);
  return f;
}

CircleFit fitCircle3d(const std::vector<Eigen::Vector3d>& pts) {
  const int n = static_cast<int>(pts.size());
  if (n < 3) throw Error("circle fit needs at least 3 points, got " + std::to_string(n));
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  CircleFit c;
  c.normal = eig.eigenvectors().col(0);
  const Eigen::Vector3d u = eig.eigenvectors().col(2), v = c.normal.cross(u);
  // 2-D Kåsa fit in the plane: x² + y² = 2 a x + 2 b y + k.
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const double x = (pts[i] - mean).dot(u), y = (pts[i] - mean).dot(v);
    A.row(i) << 2 * x, 2 * y, 1.0;
    b[i] = x * x + y * y;
  }
  const Eigen::Vector3d s = A.colPivHouseholderQr().solve(b);
  const double r2 = s[2] + s[0] * s[0] + s[1] * s[1];
  if (!(r2 > 0) || !std::isfinite(r2)) throw Error("circle fit: degenerate points (all on a line?)");
  c.radius = std::sqrt(r2);
  c.centre = mean + s[0] * u + s[1] * v;
  double ss = 0;
  for (const auto& p : pts) {
    const Eigen::Vector3d d = p - c.centre;
    const double inplane = (d - d.dot(c.normal) * c.normal).norm() - c.radius;
    ss += inplane * inplane + d.dot(c.normal) * d.dot(c.normal);
  }
  c.rms = std::sqrt(ss / n);
  return c;
}

AxisCalibration calibrateAxis(const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& angles_deg,
                              const Eigen::Vector4d& table) {
  if (centres.size() != angles_deg.size()) throw Error("axis calibration: one angle per view needed");
  if (centres.size() < 3) throw Error("axis calibration needs at least 3 views, got " + std::to_string(centres.size()));
  const CircleFit c = fitCircle3d(centres);
  AxisCalibration cal;
  cal.views = static_cast<int>(centres.size());
  const Eigen::Vector3d up = table.head<3>().normalized();
  cal.axis = c.normal.dot(up) >= 0 ? c.normal : Eigen::Vector3d(-c.normal);
  cal.target_radius = c.radius;
  cal.circle_rms = c.rms;
  // Where the axis meets the table plane.
  const double denom = table.head<3>().dot(cal.axis);
  if (std::abs(denom) < 1e-6) throw Error("axis calibration: the fitted axis lies in the table plane");
  const double t = -(table.head<3>().dot(c.centre) + table[3]) / denom;
  cal.origin = c.centre + t * cal.axis;

  // x towards the target in the first view; angles of the others about the axis.
  auto radial = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - c.centre;
    return Eigen::Vector3d(d - d.dot(cal.axis) * cal.axis).normalized();
  };
  const Eigen::Vector3d x0 = radial(centres[0]), y0 = cal.axis.cross(x0);
  // Does the reported angle grow counter-clockwise seen from above (right-handed about "up")?
  double agree = 0, disagree = 0;
  std::vector<double> fitted(centres.size());
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const Eigen::Vector3d r = radial(centres[i]);
    fitted[i] = std::atan2(r.dot(y0), r.dot(x0)) * 180.0 / M_PI;
    auto wrap = [](double a) { a = std::fmod(a, 360.0); if (a > 180) a -= 360; if (a < -180) a += 360; return a; };
    const double reported = angles_deg[i] - angles_deg[0];
    agree += std::abs(wrap(fitted[i] - reported));
    disagree += std::abs(wrap(fitted[i] + reported));
  }
  cal.reported_angles_clockwise = disagree < agree;
  const double sgn = cal.reported_angles_clockwise ? -1.0 : 1.0;
  double ss = 0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    double d = std::fmod(fitted[i] - sgn * (angles_deg[i] - angles_deg[0]), 360.0);
    if (d > 180) d -= 360;
    if (d < -180) d += 360;
    ss += d * d;
  }
  cal.angle_rms_deg = std::sqrt(ss / centres.size());

  // Turntable frame at reported 0°: rotate back from the first view's angle.
  const double a0 = sgn * angles_deg[0] * M_PI / 180.0;
  const Eigen::Vector3d x = std::cos(a0) * x0 - std::sin(a0) * y0;
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 1>(0, 0) = x;
  T.block<3, 1>(0, 1) = cal.axis.cross(x);
  T.block<3, 1>(0, 2) = cal.axis;
  T.block<3, 1>(0, 3) = cal.origin;
  cal.camera_from_turntable = T;
  return cal;
}

SphereTargetObservation observeSphereTarget(const Cloud& view, const FilterOptions& filter) {
  FilterReport rep;
  FilterOptions o = filter;
  o.remove_plane = true;
  const Cloud rest = filterCloud(view, o, &rep);
  if (!rep.plane_found) throw Error("no table plane in the view (is the turntable in sight?)");
  SphereTargetObservation obs;
  obs.table_plane = rep.plane.cast<double>();
  std::vector<Eigen::Vector3f> pts;
  for (const auto& p : rest.points)
    if (Cloud::isValid(p)) pts.push_back(p);
  obs.points = pts.size();
  if (pts.size() < 30) throw Error("only " + std::to_string(pts.size()) + " target points above the table");
  obs.sphere = fitSphere(pts);
  return obs;
}

}  // namespace keyturn
