#include "keyturn/rig/axis_calibration_run.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset.h"

namespace keyturn::rig {
namespace {

constexpr double kMinTargetCircle = 0.01;  // m: a ball standing ~6 cm off the axis goes round on ~6 cm
constexpr double kMaxAngleRmsDeg = 1.0;    // a fixed ball on a well-scaled pose source: ~0.05°
const char* const kNotATarget =
    ": not a sphere-target sequence (a ball of ~6 cm standing off-centre; simulated: the mesh "
    "builtin:sphere-target), or the ball moved, or the pose source's scale is wrong; nothing written";

nlohmann::json matrixJson(const Eigen::Matrix4d& m) {
  nlohmann::json j = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) j.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return j;
}

}  // namespace

DatasetAxisCalibration calibrateAxisFromDataset(const AxisSequence& a,
                                                const std::function<void(const std::string&, const std::string&)>& skipped,
                                                const std::function<void(std::size_t, std::size_t)>& view_done) {
  std::vector<dataset::ViewRecord> views;
  for (const auto& v : dataset::Dataset::readManifest(a.dataset))
    if ((a.cls.empty() || v.key.cls == a.cls) && (a.instance.empty() || v.key.instance == a.instance) &&
        (a.elevation.empty() || v.key.elevation == a.elevation))
      views.push_back(v);
  if (views.size() < 3) throw Error(a.dataset + ": axis calibration needs at least 3 views, found " + std::to_string(views.size()));
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> angles;
  Eigen::Vector4d table = Eigen::Vector4d::Zero();
  double radius = 0;
  if (view_done) view_done(0, views.size());
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string pcd = a.dataset + "/" + views[i].pcd();
    try {
      const SphereTargetObservation obs = observeSphereTarget(loadCloud(pcd));
      centres.push_back(obs.sphere.centre);
      angles.push_back(views[i].measured_deg);
      table += obs.table_plane;
      radius += obs.sphere.radius;
    } catch (const Error& e) {
      if (skipped) skipped(pcd, e.what());
    }
    if (view_done) view_done(i + 1, views.size());
  }
  if (centres.size() < 3) throw Error(a.dataset + ": the sphere target was found in only " + std::to_string(centres.size()) + " views");
  table /= static_cast<double>(centres.size());
  table.head<3>().normalize();
  DatasetAxisCalibration out{calibrateAxis(centres, angles, table), radius / static_cast<double>(centres.size()), a.dataset};
  const AxisCalibration& cal = out.axis;
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
  return out;
}

void writeAxisCalibration(const std::string& path, const DatasetAxisCalibration& c) {
  const AxisCalibration& cal = c.axis;
  nlohmann::json j = {{"format", "keyturn-axis-calibration"},
                      {"version", 1},
                      {"axis", {cal.axis.x(), cal.axis.y(), cal.axis.z()}},
                      {"origin", {cal.origin.x(), cal.origin.y(), cal.origin.z()}},
                      {"camera_from_turntable", matrixJson(cal.camera_from_turntable)},
                      {"target_circle_radius_m", cal.target_radius},
                      {"target_sphere_radius_m", c.sphere_radius},
                      {"circle_rms_m", cal.circle_rms},
                      {"angle_rms_deg", cal.angle_rms_deg},
                      {"reported_angles_clockwise", cal.reported_angles_clockwise},
                      {"views", cal.views},
                      {"source", c.source}};
  writeFileDurably(path, j.dump(2) + "\n");
}

}  // namespace keyturn::rig
