#pragma once
// Poses of views in one common frame, read from the files users already have.
// Every format ends as world_from_view: a point p of the view lies at
// world_from_view · p in the common frame. Each format's own convention:
//   keyturn  [ignored tokens…] VIEW_FILE tx ty tz qx qy qz qw    common = R(q) p + t
//   stanford .conf of `camera tx ty tz qx qy qz qw` (the viewer's camera, ignored) and
//            `bmesh VIEW_FILE tx ty tz qx qy qz qw` lines           common = R(q)ᵀ p + t
//   tum      `timestamp tx ty tz qx qy qz qw` (camera to world)     common = R(q) p + t,
//            views matched by a view list or by file names that are timestamps
//   matrix   VIEW_FILE m00 m01 … m33 (row-major 4 × 4)             common = M · [p 1]
// (metres; unit quaternions, w last.) '#' lines and blank lines are skipped;
// relative paths are relative to the file that names them.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "keyturn/core/error.h"

namespace keyturn {

enum class PoseFormat { Auto, Keyturn, Stanford, Tum, Matrix };

PoseFormat parsePoseFormat(const std::string& name);  // auto, keyturn, stanford, tum, matrix; throws keyturn::Error
std::string poseFormatName(PoseFormat f);

struct PoseListEntry {
  std::string file;
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();
  int line = 0;  // of the pose in its file
};

struct PoseReadOptions {
  PoseFormat format = PoseFormat::Auto;
  std::string views;    // tum only: a list of `FILE` (in trajectory order) or `TIMESTAMP FILE` lines
  double max_time_difference_s = 0.02;  // tum: a view's timestamp to its pose's (TUM's associate.py default)
  bool invert = false;  // use world_from_view⁻¹ (for files written the other way round)
};

// The format a pose file's name and first pose line show; throws keyturn::Error when they show none.
PoseFormat detectPoseFormat(const std::string& path);

// A TUM trajectory whose views are neither listed (PoseReadOptions::views) nor found by their
// timestamps: a front end may say how its user lists them.
class MissingViewListError : public Error {
 public:
  using Error::Error;
};

// Throws keyturn::Error naming the file and line of the first bad line and what was wrong.
std::vector<PoseListEntry> readPoses(const std::string& path, const PoseReadOptions& options = PoseReadOptions());

}  // namespace keyturn
