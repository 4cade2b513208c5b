#pragma once
// Turntable axis calibration, as open turntable scanners do it: a target fixed
// off-centre on the table traces a circle as the table turns; the circle's
// normal is the rotation axis and its centre a point on it. keyturn's target is
// a sphere, whose fitted centre does not depend on the viewpoint.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/filter.h"

namespace keyturn {

struct SphereFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  double rms = 0;  // of |p - c| - r
};

// Least squares (algebraic, then Gauss–Newton on the geometric distance).
// Throws keyturn::Error for fewer than 4 points or a degenerate set.
SphereFit fitSphere(const std::vector<Eigen::Vector3f>& points);

struct CircleFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit; sign arbitrary
  double radius = 0;
  double rms = 0;
};

// Circle through 3-D points: best plane (PCA), then a 2-D least-squares circle
// in it. Throws for fewer than 3 points.
CircleFit fitCircle3d(const std::vector<Eigen::Vector3d>& points);

struct AxisCalibration {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // camera frame, unit, "up" (towards the camera side of the table)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // axis ∩ table plane, camera frame (m)
  Eigen::Matrix4d camera_from_turntable = Eigen::Matrix4d::Identity();  // at 0°: x towards the target
  double target_radius = 0;   // circle radius of the target centre (m)
  double circle_rms = 0;      // m
  double angle_rms_deg = 0;   // fitted vs reported turntable angles
  bool reported_angles_clockwise = false;  // the pose source counts the other way round
  int views = 0;
};

// centres: the target centre in each view (camera frame); angles: the
// turntable angle reported for each view; table: the table plane (n, d) with
// n·x + d = 0 in the camera frame, n towards the camera.
AxisCalibration calibrateAxis(const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& angles_deg,
                              const Eigen::Vector4d& table_plane);

// One calibration view: the table plane (removed by the filter) and the centre
// of the sphere target (the largest remaining cluster). Throws when either is missing.
struct SphereTargetObservation {
  Eigen::Vector4d table_plane = Eigen::Vector4d::Zero();
  SphereFit sphere;
  std::size_t points = 0;
};
SphereTargetObservation observeSphereTarget(const Cloud& view, const FilterOptions& filter = FilterOptions());

}  // namespace keyturn
