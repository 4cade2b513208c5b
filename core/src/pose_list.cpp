#include "keyturn/core/pose_list.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "keyturn/core/error.h"

namespace fs = std::filesystem;

namespace keyturn {

PoseFormat parsePoseFormat(const std::string& n) {
  if (n == "auto") return PoseFormat::Auto;
  if (n == "keyturn") return PoseFormat::Keyturn;
  if (n == "stanford") return PoseFormat::Stanford;
  if (n == "tum") return PoseFormat::Tum;
  if (n == "matrix") return PoseFormat::Matrix;
  throw Error("pose format '" + n + "': expected auto, keyturn, stanford, tum or matrix");
}

std::string poseFormatName(PoseFormat f) {
  switch (f) {
    case PoseFormat::Auto: return "auto";
    case PoseFormat::Keyturn: return "keyturn";
    case PoseFormat::Stanford: return "stanford";
    case PoseFormat::Tum: return "tum";
    case PoseFormat::Matrix: return "matrix";
  }
  return "?";
}

namespace {

struct Line {
  int number = 0;
  std::vector<std::string> tok;
};

// The data lines of a file: no blank lines, no '#' comments.
std::vector<Line> dataLines(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": no such " + what);
  std::vector<Line> out;
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    Line l{n, {}};
    std::istringstream ss(text);
    for (std::string t; ss >> t;) l.tok.push_back(t);
    if (l.tok.empty()) continue;  // only whitespace the tokenizer skips (\v, \f)
    out.push_back(std::move(l));
  }
  return out;
}

bool isNumber(const std::string& t, double* value = nullptr) {
  try {
    std::size_t used = 0;
    const double v = std::stod(t, &used);
    if (used != t.size() || !std::isfinite(v)) return false;
    if (value) *value = v;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::string where(const std::string& path, const Line& l) { return path + ": line " + std::to_string(l.number) + ": "; }

// n numbers from tok[first…].
std::vector<double> numbers(const std::string& path, const Line& l, std::size_t first, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!isNumber(l.tok[first + i], &v[i])) throw Error(where(path, l) + "'" + l.tok[first + i] + "' is not a number");
  return v;
}

// tx ty tz qx qy qz qw → [R t]; transpose_rotation for Stanford's convention.
Eigen::Matrix4d fromTranslationQuaternion(const std::string& path, const Line& l, const std::vector<double>& v,
                                          bool transpose_rotation) {
  Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // w, x, y, z
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > 1e-3)
    throw Error(where(path, l) + "quaternion is not unit length (|q| = " + std::to_string(norm) + ")");
  q.normalize();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = transpose_rotation ? q.toRotationMatrix().transpose() : q.toRotationMatrix();
  T.topRightCorner<3, 1>() = Eigen::Vector3d(v[0], v[1], v[2]);
  return T;
}

std::string resolve(const fs::path& base, const std::string& file) {
  fs::path p = file;
  return (p.is_relative() ? base / p : p).string();
}

std::vector<PoseListEntry> readKeyturn(const std::string& path, const std::vector<Line>& lines) {
  const fs::path base = fs::path(path).parent_path();
  std::vector<PoseListEntry> out;
  for (const auto& l : lines) {
    if (l.tok.size() < 8)
      throw Error(where(path, l) + "expected VIEW_FILE tx ty tz qx qy qz qw, found " + std::to_string(l.tok.size()) +
                  " fields");
    const auto v = numbers(path, l, l.tok.size() - 7, 7);
    out.push_back({resolve(base, l.tok[l.tok.size() - 8]), fromTranslationQuaternion(path, l, v, false), l.number});
  }
  return out;
}

std::vector<PoseListEntry> readStanford(const std::string& path, const std::vector<Line>& lines) {
  const fs::path base = fs::path(path).parent_path();
  std::vector<PoseListEntry> out;
  for (const auto& l : lines) {
    const std::string& key = l.tok[0];
    if (key == "camera") {
      if (l.tok.size() != 8)
        throw Error(where(path, l) + "expected camera tx ty tz qx qy qz qw, found " + std::to_string(l.tok.size()) +
                    " fields");
      fromTranslationQuaternion(path, l, numbers(path, l, 1, 7), true);  // checked, not used: the viewer's camera
    } else if (key == "bmesh") {
      if (l.tok.size() != 9)
        throw Error(where(path, l) + "expected bmesh FILE tx ty tz qx qy qz qw, found " + std::to_string(l.tok.size()) +
                    " fields");
      out.push_back({resolve(base, l.tok[1]), fromTranslationQuaternion(path, l, numbers(path, l, 2, 7), true), l.number});
    } else {
      throw Error(where(path, l) + "expected a camera or bmesh line, found '" + key + "'");
    }
  }
  return out;
}

std::vector<PoseListEntry> readMatrix(const std::string& path, const std::vector<Line>& lines) {
  const fs::path base = fs::path(path).parent_path();
  std::vector<PoseListEntry> out;
  for (const auto& l : lines) {
    if (l.tok.size() != 17)
      throw Error(where(path, l) + "expected VIEW_FILE and 16 numbers of a row-major 4 × 4, found " +
                  std::to_string(l.tok.size()) + " fields");
    const auto v = numbers(path, l, 1, 16);
    Eigen::Matrix4d T;
    for (int i = 0; i < 16; ++i) T(i / 4, i % 4) = v[i];
    if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6)
      throw Error(where(path, l) + "last row is not 0 0 0 1");
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3 || R.determinant() < 0)
      throw Error(where(path, l) + "the upper-left 3 × 3 is not a rotation");
    out.push_back({resolve(base, l.tok[0]), T, l.number});
  }
  return out;
}

struct Stamped {
  double t;
  PoseListEntry pose;
};

// TUM trajectories: the view files come from a list (in order, or stamped) or from
// file names that are timestamps beside the trajectory.
std::vector<PoseListEntry> readTum(const std::string& path, const std::vector<Line>& lines, const PoseReadOptions& o) {
  std::vector<Stamped> poses;
  for (const auto& l : lines) {
    if (l.tok.size() != 8)
      throw Error(where(path, l) + "expected timestamp tx ty tz qx qy qz qw, found " + std::to_string(l.tok.size()) +
                  " fields");
    const auto v = numbers(path, l, 0, 8);
    poses.push_back({v[0], {"", fromTranslationQuaternion(path, l, {v.begin() + 1, v.end()}, false), l.number}});
  }
  std::vector<std::pair<double, std::string>> stamped;  // view timestamp, file
  if (!o.views.empty()) {
    const fs::path base = fs::path(o.views).parent_path();
    const auto list = dataLines(o.views, "view list");
    if (list.empty()) throw Error(o.views + ": no views listed");
    const bool with_time = list[0].tok.size() == 2;
    for (const auto& l : list) {
      if (l.tok.size() != (with_time ? 2u : 1u))
        throw Error(where(o.views, l) + (with_time ? "expected TIMESTAMP FILE" : "expected FILE") + ", found " +
                    std::to_string(l.tok.size()) + " fields");
      double t = 0;
      if (with_time && !isNumber(l.tok[0], &t)) throw Error(where(o.views, l) + "'" + l.tok[0] + "' is not a timestamp");
      stamped.emplace_back(with_time ? t : std::nan(""), resolve(base, l.tok.back()));
    }
    if (!with_time) {
      if (stamped.size() != poses.size())
        throw Error(o.views + ": lists " + std::to_string(stamped.size()) + " views for the " +
                    std::to_string(poses.size()) + " poses of " + path + " (give TIMESTAMP FILE lines to match by time)");
      std::vector<PoseListEntry> out;
      for (std::size_t i = 0; i < poses.size(); ++i) {
        out.push_back(poses[i].pose);
        out.back().file = stamped[i].second;
      }
      return out;
    }
  } else {
    const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string ext = e.path().extension().string();
      double t = 0;
      if ((ext == ".pcd" || ext == ".ply") && isNumber(e.path().stem().string(), &t)) stamped.emplace_back(t, e.path().string());
    }
    std::sort(stamped.begin(), stamped.end());
    if (stamped.empty())
      throw MissingViewListError(path + ": a TUM trajectory needs its views: a view list, or TIMESTAMP.pcd/.ply files beside it");
  }
  std::vector<PoseListEntry> out;
  for (const auto& [t, file] : stamped) {
    const auto best = std::min_element(poses.begin(), poses.end(), [t = t](const Stamped& a, const Stamped& b) {
      return std::abs(a.t - t) < std::abs(b.t - t);
    });
    const double dt = std::abs(best->t - t);
    if (dt > o.max_time_difference_s)
      throw Error(file + ": no pose in " + path + " within " + std::to_string(o.max_time_difference_s * 1000).substr(0, 4) +
                  " ms of its timestamp (nearest " + std::to_string(dt) + " s)");
    out.push_back(best->pose);
    out.back().file = file;
  }
  return out;
}

PoseFormat formatOf(const std::string& path, const Line& l) {
  if (fs::path(path).extension() == ".conf" || l.tok[0] == "camera" || l.tok[0] == "bmesh") return PoseFormat::Stanford;
  const bool all_numbers = std::all_of(l.tok.begin(), l.tok.end(), [](const std::string& t) { return isNumber(t); });
  if (all_numbers && l.tok.size() == 8) return PoseFormat::Tum;
  if (l.tok.size() == 17 && !isNumber(l.tok[0]) &&
      std::all_of(l.tok.begin() + 1, l.tok.end(), [](const std::string& t) { return isNumber(t); }))
    return PoseFormat::Matrix;
  // Otherwise the parser of the format the line comes closest to names what is wrong with it.
  return all_numbers ? PoseFormat::Tum : PoseFormat::Keyturn;
}

}  // namespace

PoseFormat detectPoseFormat(const std::string& path) {
  const auto lines = dataLines(path, "pose file");
  if (lines.empty()) throw Error(path + ": no poses listed");
  return formatOf(path, lines[0]);
}

std::vector<PoseListEntry> readPoses(const std::string& path, const PoseReadOptions& o) {
  const auto lines = dataLines(path, "pose file");
  if (lines.empty()) throw Error(path + ": no poses listed");
  const PoseFormat f = o.format == PoseFormat::Auto ? formatOf(path, lines[0]) : o.format;
  if (!o.views.empty() && f != PoseFormat::Tum)
    throw Error(path + ": a view list is for a TUM trajectory only; this is " + poseFormatName(f));
  std::vector<PoseListEntry> out = f == PoseFormat::Stanford ? readStanford(path, lines)
                                   : f == PoseFormat::Tum    ? readTum(path, lines, o)
                                   : f == PoseFormat::Matrix ? readMatrix(path, lines)
                                                             : readKeyturn(path, lines);
  if (out.empty()) throw Error(path + ": no views listed");
  if (o.invert)
    for (auto& e : out) e.world_from_view = e.world_from_view.inverse().eval();
  return out;
}

}  // namespace keyturn
