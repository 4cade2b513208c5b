#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "keyturn/core/axis_calibration.h"
#include "keyturn/core/error.h"
#include "keyturn/sim/tof_view.h"

using namespace keyturn;

TEST(AxisCalibration, SphereFitRecoversCentreAndRadiusFromACap) {
  std::mt19937 rng(2);
  std::normal_distribution<float> g(0.f, 1.f), noise(0.f, 0.0005f);
  std::vector<Eigen::Vector3f> pts;
  const Eigen::Vector3f c(0.1f, -0.05f, 0.8f);
  while (pts.size() < 800) {
    const Eigen::Vector3f d = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    if (d.z() > -0.3f) continue;  // only the cap facing the camera (−z) is seen
    pts.push_back(c + 0.03f * d + Eigen::Vector3f(noise(rng), noise(rng), noise(rng)));
  }
  const SphereFit f = fitSphere(pts);
  EXPECT_LT((f.centre - c.cast<double>()).norm(), 0.001);
  EXPECT_NEAR(f.radius, 0.03, 0.001);
  EXPECT_THROW(fitSphere({pts[0], pts[1], pts[2]}), Error);
}

TEST(AxisCalibration, CircleFitOfATiltedCircle) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.7, 0.5).normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u), c(0.3, 0.1, 1.2);
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k < 12; ++k) pts.push_back(c + 0.07 * (std::cos(k * 0.5) * u + std::sin(k * 0.5) * v));
  const CircleFit f = fitCircle3d(pts);
  EXPECT_LT((f.centre - c).norm(), 1e-9);
  EXPECT_NEAR(f.radius, 0.07, 1e-9);
  EXPECT_NEAR(std::abs(f.normal.dot(n)), 1.0, 1e-9);
}

TEST(AxisCalibration, RecoversTheSimulatedTurntableAxis) {
  // Views of the sphere target every 30°, with sensor noise, from 45° elevation.
  const sim::Mesh target = sim::makeSphereTargetMesh();
  sim::TofViewRenderer r(target);
  sim::SceneView v;
  v.elevation_deg = 45;
  v.distance = 0.6;
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> angles;
  Eigen::Vector4d table = Eigen::Vector4d::Zero();
  for (int a = 0; a < 360; a += 30) {
    v.turntable_deg = a;
    v.seed = static_cast<std::uint64_t>(a) + 1;
    const SphereTargetObservation obs = observeSphereTarget(r.render(v));
    EXPECT_NEAR(obs.sphere.radius, 0.03, 0.002);
    centres.push_back(obs.sphere.centre);
    angles.push_back(a);
    table += obs.table_plane;
  }
  table /= static_cast<double>(centres.size());
  const AxisCalibration cal = calibrateAxis(centres, angles, table);
  v.turntable_deg = 0;
  const Eigen::Matrix4d truth = sim::cameraFromTurntable(target, v);
  const Eigen::Vector3d true_axis = truth.block<3, 1>(0, 2), true_origin = truth.block<3, 1>(0, 3);
  EXPECT_LT(std::acos(std::min(1.0, cal.axis.dot(true_axis))) * 180 / M_PI, 1.0);
  EXPECT_LT((cal.origin - true_origin).norm(), 0.005);
  EXPECT_NEAR(cal.target_radius, 0.07, 0.003);
  EXPECT_FALSE(cal.reported_angles_clockwise);
  EXPECT_LT(cal.angle_rms_deg, 1.0);
  // The turntable frame's x points at the target at 0°, as the simulated world's does.
  const Eigen::Vector3d true_x = truth.block<3, 1>(0, 0);
  const Eigen::Vector3d cal_x = cal.camera_from_turntable.block<3, 1>(0, 0);
  EXPECT_GT(cal_x.dot(true_x), 0.999);
}

TEST(AxisCalibration, AnglesCountedTheOtherWayAreDetected) {
  const Eigen::Vector3d up = Eigen::Vector3d(0, -0.5, -0.866).normalized();
  const Eigen::Vector3d u = up.unitOrthogonal(), w = up.cross(u), c(0, 0.1, 0.9);
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> angles;
  for (int k = 0; k < 8; ++k) {
    const double a = k * 45 * M_PI / 180;
    centres.push_back(c + 0.07 * (std::cos(a) * u + std::sin(a) * w));
    angles.push_back(-k * 45.0);  // the pose source reports clockwise
  }
  const Eigen::Vector4d table(up.x(), up.y(), up.z(), -up.dot(c - 0.03 * up));
  const AxisCalibration cal = calibrateAxis(centres, angles, table);
  EXPECT_TRUE(cal.reported_angles_clockwise);
  EXPECT_LT(cal.angle_rms_deg, 1e-6);
}
