// keyturn calibrate-axis: the turntable's rotation axis from a captured
// sequence of the sphere target (keyturn capture --mesh builtin:sphere-target
// in simulation; a ~6 cm ball standing off-centre on a real table).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "keyturn/core/axis_calibration.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/rig/dataset.h"
#include "keyturn/core/durable_file.h"
#include "progress.h"

namespace keyturn::app {
namespace {

constexpr double kMinTargetCircle = 0.01;  // m: a ball standing ~6 cm off the axis goes round on ~6 cm
constexpr double kMaxAngleRmsDeg = 1.0;    // a fixed ball on a well-scaled pose source: ~0.05°
const char* const kNotATarget =
    ": not a sphere-target sequence (a ball of ~6 cm standing off-centre; simulated: capture --mesh "
    "builtin:sphere-target), or the ball moved, or the pose source's scale is wrong; nothing written";

struct CalibrateArgs {
  std::string dataset, out, cls, instance, elevation;
};

nlohmann::json matrixJson(const Eigen::Matrix4d& m) {
  nlohmann::json j = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) j.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return j;
}

int runCalibrate(const CalibrateArgs& a) {
  std::vector<rig::ViewRecord> views;
  for (const auto& v : rig::Dataset::readManifest(a.dataset))
    if ((a.cls.empty() || v.key.cls == a.cls) && (a.instance.empty() || v.key.instance == a.instance) &&
        (a.elevation.empty() || v.key.elevation == a.elevation))
      views.push_back(v);
  if (views.size() < 3) throw Error(a.dataset + ": axis calibration needs at least 3 views, found " + std::to_string(views.size()));
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> angles;
  Eigen::Vector4d table = Eigen::Vector4d::Zero();
  double radius = 0;
  Progress progress("calibrate", views.size(), true);
  for (const auto& v : views) {
    const std::string pcd = a.dataset + "/" + v.pcd();
    try {
      const SphereTargetObservation obs = observeSphereTarget(loadCloud(pcd));
      centres.push_back(obs.sphere.centre);
      angles.push_back(v.measured_deg);
      table += obs.table_plane;
      radius += obs.sphere.radius;
    } catch (const Error& e) {
      std::cerr << "keyturn calibrate-axis: skipping " << pcd << ": " << e.what() << "\n";
    }
    progress.advance();
  }
  progress.finish();
  if (centres.size() < 3) throw Error(a.dataset + ": the sphere target was found in only " + std::to_string(centres.size()) + " views");
  table /= static_cast<double>(centres.size());
  table.head<3>().normalize();
  const AxisCalibration cal = calibrateAxis(centres, angles, table);
  // A sequence without an off-centre ball still fits "a sphere" per view (the object's own surface),
  // and its axis would be wrong: refused rather than written (the ball's centre must go round).
  char why[200];
  if (cal.target_radius < kMinTargetCircle) {
    std::snprintf(why, sizeof why, "the target's centre moves on a circle of only %.1f mm (at least %.0f mm needed)",
                  cal.target_radius * 1000, kMinTargetCircle * 1000);
    throw Error(a.dataset + ": " + why + kNotATarget);
  }
  if (cal.angle_rms_deg > kMaxAngleRmsDeg) {
    std::snprintf(why, sizeof why, "reported and fitted turntable angles disagree by %.2f° rms (at most %.0f°)",
                  cal.angle_rms_deg, kMaxAngleRmsDeg);
    throw Error(a.dataset + ": " + why + kNotATarget);
  }
  nlohmann::json j = {{"format", "keyturn-axis-calibration"},
                      {"version", 1},
                      {"axis", {cal.axis.x(), cal.axis.y(), cal.axis.z()}},
                      {"origin", {cal.origin.x(), cal.origin.y(), cal.origin.z()}},
                      {"camera_from_turntable", matrixJson(cal.camera_from_turntable)},
                      {"target_circle_radius_m", cal.target_radius},
                      {"target_sphere_radius_m", radius / centres.size()},
                      {"circle_rms_m", cal.circle_rms},
                      {"angle_rms_deg", cal.angle_rms_deg},
                      {"reported_angles_clockwise", cal.reported_angles_clockwise},
                      {"views", cal.views},
                      {"source", a.dataset}};
  writeFileDurably(a.out, j.dump(2) + "\n");
  std::printf("axis (camera frame) %.4f %.4f %.4f through %.4f %.4f %.4f m; target circle r = %.1f mm; "
              "circle rms %.2f mm, angle rms %.2f° over %d views → %s\n",
              cal.axis.x(), cal.axis.y(), cal.axis.z(), cal.origin.x(), cal.origin.y(), cal.origin.z(),
              cal.target_radius * 1000, cal.circle_rms * 1000, cal.angle_rms_deg, cal.views, a.out.c_str());
  if (cal.reported_angles_clockwise)
    std::printf("warning: the pose source's angles grow clockwise seen from above; set \"direction\": -1 in its profile\n");
  return 0;
}

}  // namespace

Command addCalibrateCommand(CLI::App& app) {
  auto a = std::make_shared<CalibrateArgs>();
  auto* cmd = app.add_subcommand("calibrate-axis", "Fit the turntable's rotation axis from a sphere-target sequence");
  cmd->add_option("dataset", a->dataset, "Dataset holding the calibration sequence")->required();
  cmd->add_option("--class", a->cls, "Only views of this class");
  cmd->add_option("--instance", a->instance, "Only views of this instance");
  cmd->add_option("--elevation", a->elevation, "Only views at this elevation label");
  cmd->add_option("--out,-o", a->out, "Calibration JSON to write")->required();
  return {cmd, [a] { return runCalibrate(*a); }};
}

}  // namespace keyturn::app
