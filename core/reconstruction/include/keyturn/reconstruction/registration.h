#pragma once
// Multi-view registration: views of one object with initial world_from_view poses, refined so
// that they agree. Two pose models:
//   Free       every view's pose but the reference's is free (scans, hand-held captures):
//              pairwise point-to-plane ICP (coarse to fine) between overlapping views into a pose
//              graph, Open3D's global optimisation (Levenberg–Marquardt with line processes),
//              then rounds of fine pairwise ICP from the optimised poses and optimisation again.
//   Turntable  views from a turntable (poses = a rig camera's pose ∘ the table's angle): only the
//              rig is refined, one rigid correction per rig camera (the axis direction, a point on
//              it and the angle offset, as seen by that camera), so views cannot drift along an
//              object's symmetry the way free poses do. Where a camera's views found the table,
//              its plane holds that camera's tilt and height (the platter is square to the axis).
// The reference view keeps its pose in both (the common frame's gauge).
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/core/error.h"

namespace keyturn::reconstruction {

enum class PoseModel { Free, Turntable };
const char* poseModelName(PoseModel m);  // "free", "turntable"

struct RegistrationView {
  std::string name;                     // in messages (the view's file)
  std::vector<Eigen::Vector3f> points;  // valid points, the view's own frame (metres)
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();
  int rig_camera = 0;  // Turntable: which rig camera (e.g. elevation) took it
  // Turntable: the rig camera's support plane in the view's frame (n·x + d = 0) and the correction
  // that levels it (levelRigOnSupport), applied on the right of the pose before refining; that
  // camera then only turns about the turntable's axis and slides along the table, so the plane stays
  // level. Zero plane: none, all six degrees of freedom refined.
  Eigen::Vector4d support = Eigen::Vector4d::Zero();
  Eigen::Matrix4d level = Eigen::Matrix4d::Identity();
};

struct RegistrationOptions {
  PoseModel model = PoseModel::Free;
  bool refine = true;            // false: keep the poses, only measure them
  double voxel_m = 0;            // finest working resolution; 0: 1/250 of the object's size, at least the views' point spacing
  double initial_distance_m = 0;  // first correspondence distance, the poses' expected error; 0: 1/20 of the object
  double min_overlap = 0.2;      // a pair overlaps when this fraction of either view has a close point
  int max_partners = 8;          // per view, the best-overlapping partners kept as pairs
  int joint_rounds = 2;          // Free: rounds of fine pairwise ICP and graph optimisation after the first
  int reference = 0;             // the view whose pose is kept
  bool level_on_support = true;  // Turntable: the support plane holds each rig camera's tilt and height (support.h)
  // Turntable, levelled: a camera's turn about the axis is refined only when the object fixes it this
  // well (a fraction of what the turn would cost if every point moved with it); else the calibration's.
  double min_turn_information = 0.02;
};

struct RegistrationPair {
  int a = 0, b = 0;
  double overlap = 0;      // under the initial poses
  double fitness = 0;      // pairwise ICP's, at the finest distance (Free)
  bool pruned = false;     // dropped by the global optimisation's line process
};

struct RegistrationResult {
  std::vector<Eigen::Matrix4d> world_from_view;
  std::vector<double> residual_before_m, residual_after_m;  // per view: median distance to the other views
  std::vector<double> overlap_before, overlap_after;          // per view: fraction of points with a close neighbour
  std::vector<RegistrationPair> pairs;
  double voxel_m = 0;
  bool turns_kept = false;  // Turntable, levelled: the cameras' turns about the axis kept as calibrated (the object does not fix them)
};

struct RegistrationProgress {
  std::function<void(const std::string& stage, std::size_t total)> begin = [](const std::string&, std::size_t) {};
  std::function<void()> step = [] {};
  std::function<void()> end = [] {};
};

// Views that do not overlap the others (under the initial poses) cannot be registered.
class NoOverlapError : public Error {
 public:
  using Error::Error;
};

// Throws keyturn::Error (fewer than two views, too few points) or NoOverlapError.
RegistrationResult registerViews(const std::vector<RegistrationView>& views, const RegistrationOptions& options,
                                 const RegistrationProgress& progress = RegistrationProgress());

}  // namespace keyturn::reconstruction
