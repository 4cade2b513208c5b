#pragma once
// The views of one object to reconstruct, each with its world_from_view pose: a calibrated keyturn
// dataset's views (the sidecars' camera_from_turntable: turntable angle ∘ axis calibration), or any
// pose file core reads (Stanford .conf, TUM, matrices, keyturn's list), as `keyturn repeatability`
// takes them (dataset::studyViews).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/error.h"
#include "keyturn/core/pose_list.h"

namespace keyturn::reconstruction {

struct PosedView {
  std::string file;
  std::string object;     // CLASS/INSTANCE for a dataset's views, empty for a pose file's
  std::string elevation;  // a dataset's elevation (its rig camera), empty otherwise
  double angle_deg = 0;   // the turntable's angle (datasets)
  bool turntable = false; // the pose is a turntable angle ∘ a calibrated rig camera
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();
};

struct ViewSelection {
  std::string object;                   // CLASS/INSTANCE; empty: the input must hold one object
  std::vector<std::string> elevations;  // empty: all
};

// An input holding several objects and no choice among them (a front end says how to choose).
class SeveralObjectsError : public Error {
 public:
  using Error::Error;
};

// Throws keyturn::Error with one line for: no poses (a folder that is not a calibrated dataset,
// a dataset without axis calibration), views of two objects without a selection, nothing selected,
// a single view.
std::vector<PosedView> posedViews(const std::string& input, const PoseReadOptions& poses,
                                  const ViewSelection& selection = ViewSelection());

// Poses as keyturn's pose list (`VIEW_FILE tx ty tz qx qy qz qw`, common = R(q) p + t, absolute
// paths), which readPoses reads back.
std::string poseListText(const std::vector<std::string>& files, const std::vector<Eigen::Matrix4d>& world_from_view);

// Each pose but the reference's moved by a rotation of `degrees` about a random axis and a shift of
// `metres` in a random direction, both in the view's frame (seeded): the pose errors are exactly
// these amounts.
std::vector<Eigen::Matrix4d> perturbPoses(std::vector<Eigen::Matrix4d> poses, double degrees, double metres,
                                          unsigned seed, int reference = 0);

// A turntable dataset's poses as an axis calibration mis-set by `degrees` (a tilt about a horizontal
// axis) and `metres` (a horizontal shift) gives them: per rig camera (elevation) one such error of
// that camera's pose on the table, in a seeded random direction, the same for all its views.
// Throws keyturn::Error when a view has no turntable angle.
void missetAxis(std::vector<PosedView>& views, double degrees, double metres, unsigned seed);

// The rotation (degrees) and translation (metres) between two poses.
struct PoseDifference {
  double rotation_deg = 0, translation_m = 0;
};
PoseDifference poseDifference(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b);

// A turntable's axis as a camera sees it, implied by that camera's poses of one turn: the common
// rotation axis of the views' relative motions (camera frame) and its point nearest the camera.
struct ImpliedAxis {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int pairs = 0;  // view pairs used (those rotating ≥ 10° relative to each other)
};
// Throws keyturn::Error when no two views rotate by ≥ 10°.
ImpliedAxis impliedAxis(const std::vector<Eigen::Matrix4d>& world_from_view);

}  // namespace keyturn::reconstruction
