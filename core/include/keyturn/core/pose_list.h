#pragma once
// A pose list names views and their poses in one common frame, one per line:
//   [ignored tokens…] VIEW_FILE tx ty tz qx qy qz qw
// (metres; unit quaternion; the view's pose = world ← view). Lines starting with
// '#' and blank lines are skipped; relative paths are relative to the list.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace keyturn {

struct PoseListEntry {
  std::string file;
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();
  int line = 0;
};

// Throws keyturn::Error naming the file and the line number of the first bad line.
std::vector<PoseListEntry> readPoseList(const std::string& path);

}  // namespace keyturn
