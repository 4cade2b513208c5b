#include "keyturn/reconstruction/posed_views.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset_layout.h"
#include "keyturn/dataset/study_views.h"

namespace fs = std::filesystem;

namespace keyturn::reconstruction {

namespace {

bool isViewFile(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".pcd" || ext == ".png";
}

}  // namespace

std::vector<PosedView> posedViews(const std::string& input, const PoseReadOptions& poses,
                                  const ViewSelection& selection) {
  if (!fs::exists(input)) throw Error(input + ": no such dataset or pose file");
  if (!fs::is_directory(input) && isViewFile(input))
    throw Error(input + ": one view and no poses: give a calibrated dataset or a pose file naming at least two views");
  std::vector<StudyView> study;
  try {
    study = dataset::studyViews(input, poses);
  } catch (const MissingViewListError&) {
    throw;
  } catch (const Error& e) {
    if (fs::is_directory(input) && !fs::exists(dataset::manifestPath(input)))
      throw Error(input + ": no poses: a folder must be a calibrated keyturn dataset (or give a pose file)");
    throw;
  }
  if (study.empty()) throw Error(input + ": no poses in it");
  std::vector<PosedView> views;
  std::map<std::string, std::size_t> objects;
  for (const auto& s : study) {
    PosedView v;
    v.file = s.file;
    v.world_from_view = s.view_from_common.inverse();
    v.turntable = std::isfinite(s.angle_deg);
    if (v.turntable) {  // a dataset's group: CLASS/INSTANCE/eELEVATION
      v.angle_deg = s.angle_deg;
      const auto cut = s.group.rfind('/');
      v.object = s.group.substr(0, cut);
      v.elevation = cut == std::string::npos ? "" : s.group.substr(cut + 1);
    }
    ++objects[v.object];
    views.push_back(std::move(v));
  }
  if (!selection.object.empty()) {
    if (!objects.count(selection.object)) {
      std::string known;
      for (const auto& [o, n] : objects) known += (known.empty() ? "" : ", ") + (o.empty() ? "(none)" : o);
      throw Error(input + ": no views of " + selection.object + " (it holds " + known + ")");
    }
    views.erase(std::remove_if(views.begin(), views.end(), [&](const auto& v) { return v.object != selection.object; }),
                views.end());
  } else if (objects.size() > 1) {
    auto it = objects.begin();
    const std::string a = it->first, b = (++it)->first;
    throw SeveralObjectsError(input + ": views of " + std::to_string(objects.size()) + " objects (" + a + ", " + b +
                              (objects.size() > 2 ? ", …" : "") + "): choose one");
  }
  if (!selection.elevations.empty()) {
    const std::set<std::string> keep(selection.elevations.begin(), selection.elevations.end());
    views.erase(std::remove_if(views.begin(), views.end(),
                               [&](const auto& v) {
                                 return !keep.count(v.elevation) && !keep.count("e" + v.elevation) &&
                                        !(v.elevation.size() > 1 && keep.count(v.elevation.substr(1)));
                               }),
                views.end());
    if (views.empty()) throw Error(input + ": no views at the elevations asked for");
  }
  if (views.size() < 2)
    throw Error(input + ": " + std::to_string(views.size()) + " view: a reconstruction needs at least two");
  return views;
}

std::string poseListText(const std::vector<std::string>& files, const std::vector<Eigen::Matrix4d>& world_from_view) {
  std::ostringstream out;
  out << "# keyturn pose list: VIEW_FILE tx ty tz qx qy qz qw (metres; common = R(q) p + t)\n";
  out << std::setprecision(10);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const Eigen::Matrix4d& T = world_from_view[i];
    Eigen::Quaterniond q(Eigen::Matrix3d(T.topLeftCorner<3, 3>()));
    q.normalize();
    out << fs::absolute(files[i]).lexically_normal().string() << ' ' << T(0, 3) << ' ' << T(1, 3) << ' ' << T(2, 3)
        << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
  }
  return out.str();
}

std::vector<Eigen::Matrix4d> perturbPoses(std::vector<Eigen::Matrix4d> poses, double degrees, double metres,
                                          unsigned seed, int reference) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  auto direction = [&] {
    // One draw per statement: the order of a call's arguments is unspecified, and GCC and Clang
    // drew the same seed's axes in opposite orders (the sanitizer build's test input differed).
    Eigen::Vector3d d;
    d.x() = g(rng);
    d.y() = g(rng);
    d.z() = g(rng);
    return Eigen::Vector3d(d.normalized());
  };
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d axis = direction(), shift = direction();
    if (int(i) == reference) continue;
    Eigen::Matrix4d D = Eigen::Matrix4d::Identity();
    D.topLeftCorner<3, 3>() = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis).toRotationMatrix();
    poses[i] = poses[i] * D;
    poses[i].topRightCorner<3, 1>() += metres * shift;
  }
  return poses;
}

void missetAxis(std::vector<PosedView>& views, double degrees, double metres, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> turn(0, 2 * M_PI);
  std::map<std::string, Eigen::Matrix4d> correction;  // per rig camera, on the right of its poses
  for (auto& v : views) {
    if (!v.turntable) throw Error(v.file + ": no turntable angle; a mis-set axis needs a calibrated dataset's views");
    auto it = correction.find(v.elevation);
    if (it == correction.end()) {
      // The table frame as this camera's first view has it: a tilt about a horizontal axis through
      // the origin (where the axis meets the table) and a horizontal shift, one draw per statement.
      const double tilt_direction = turn(rng);
      const double shift_direction = turn(rng);
      Eigen::Matrix4d miss = Eigen::Matrix4d::Identity();
      miss.topLeftCorner<3, 3>() =
          Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d(std::cos(tilt_direction), std::sin(tilt_direction), 0))
              .toRotationMatrix();
      miss.topRightCorner<3, 1>() = metres * Eigen::Vector3d(std::cos(shift_direction), std::sin(shift_direction), 0);
      it = correction.emplace(v.elevation, v.world_from_view.inverse() * miss * v.world_from_view).first;
    }
    v.world_from_view = v.world_from_view * it->second;
  }
}

PoseDifference poseDifference(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  // atan2 of sin and cos: acos alone turns a rotation's float-precision non-orthonormality into
  // hundredths of a degree near 0°.
  const Eigen::Matrix3d R = a.topLeftCorner<3, 3>().transpose() * b.topLeftCorner<3, 3>();
  const Eigen::Vector3d s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double angle = std::atan2(s.norm() / 2, (R.trace() - 1.0) / 2.0);
  return {angle * 180.0 / M_PI, (a.topRightCorner<3, 1>() - b.topRightCorner<3, 1>()).norm()};
}

ImpliedAxis impliedAxis(const std::vector<Eigen::Matrix4d>& world_from_view) {
  // The camera is fixed and the table turns: view j relative to view i, camera frame, is a
  // rotation about the axis: x_i = M x_j with M = W_i⁻¹ W_j, and (I − R) c = t for c on it.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::vector<Eigen::Matrix4d> motions;
  for (std::size_t i = 0; i < world_from_view.size(); ++i)
    for (std::size_t j = i + 1; j < world_from_view.size(); ++j) {
      const Eigen::Matrix4d M = world_from_view[i].inverse() * world_from_view[j];
      const Eigen::AngleAxisd aa(Eigen::Matrix3d(M.topLeftCorner<3, 3>()));
      if (aa.angle() < 10 * M_PI / 180) continue;
      Eigen::Vector3d d = aa.axis();
      if (!motions.empty() && d.dot(sum) < 0) d = -d;
      sum += d * std::sin(aa.angle());  // pairs near 180° fix the axis' direction least
      motions.push_back(M);
    }
  if (motions.empty()) throw Error("the views do not turn by 10° or more relative to each other: no axis");
  ImpliedAxis out;
  out.direction = sum.normalized();
  if (out.direction.z() > 0) out.direction = -out.direction;  // one sign for reports: towards the camera (−z)
  out.pairs = int(motions.size());
  // Least squares over all motions, plus the condition that c is the axis point nearest the camera.
  Eigen::MatrixXd A(3 * motions.size() + 1, 3);
  Eigen::VectorXd b(3 * motions.size() + 1);
  for (std::size_t k = 0; k < motions.size(); ++k) {
    A.block<3, 3>(3 * k, 0) = Eigen::Matrix3d::Identity() - motions[k].topLeftCorner<3, 3>();
    b.segment<3>(3 * k) = motions[k].topRightCorner<3, 1>();
  }
  A.bottomRows<1>() = out.direction.transpose();
  b(b.size() - 1) = 0;
  out.point = A.colPivHouseholderQr().solve(b);
  return out;
}

}  // namespace keyturn::reconstruction
