#include "keyturn/core/pose_list.h"

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "keyturn/core/error.h"

namespace keyturn {

std::vector<PoseListEntry> readPoseList(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": no such pose list");
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  std::vector<PoseListEntry> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::vector<std::string> tok;
    std::istringstream ss(line);
    for (std::string t; ss >> t;) tok.push_back(t);
    const std::string where = path + ": line " + std::to_string(n) + ": ";
    if (tok.size() < 8) throw Error(where + "expected VIEW_FILE tx ty tz qx qy qz qw, found " + std::to_string(tok.size()) + " fields");
    double v[7];
    for (int i = 0; i < 7; ++i) {
      const std::string& t = tok[tok.size() - 7 + i];
      try {
        std::size_t used = 0;
        v[i] = std::stod(t, &used);
        if (used != t.size() || !std::isfinite(v[i])) throw std::invalid_argument(t);
      } catch (const std::exception&) {
        throw Error(where + "'" + t + "' is not a number");
      }
    }
    Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // w, x, y, z
    const double norm = q.norm();
    if (std::abs(norm - 1.0) > 1e-3) throw Error(where + "quaternion is not unit length (|q| = " + std::to_string(norm) + ")");
    q.normalize();
    PoseListEntry e;
    e.line = n;
    std::filesystem::path file = tok[tok.size() - 8];
    if (file.is_relative()) file = base / file;
    e.file = file.string();
    e.world_from_view.topLeftCorner<3, 3>() = q.toRotationMatrix();
    e.world_from_view.topRightCorner<3, 1>() = Eigen::Vector3d(v[0], v[1], v[2]);
    out.push_back(e);
  }
  if (out.empty()) throw Error(path + ": no poses listed");
  return out;
}

}  // namespace keyturn
