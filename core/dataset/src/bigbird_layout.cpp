// BigBIRD, the Berkeley Instance Recognition Dataset (Singh, Sha, Narayan, Achim and Abbeel, ICRA
// 2014): each object turned in 3° steps before five PrimeSense Carmines NP1 … NP5 mounted one above
// the other. Per object folder: NPi_ANGLE.h5 (dataset "depth", uint16, 100 µm units), calibration.h5
// (NPi_depth_K, NPi_ir_depth_scale, H_NPi_ir_from_NP5, and the colour camera's NPi_rgb_K and
// H_NPi_from_NP5), poses/NP5_ANGLE_pose.h5 (H_table_from_reference_camera: the calibration board on
// the turntable as NP5 saw it) and masks/NPi_ANGLE_mask.pbm (black = object, in the colour image).
#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "h5_file.h"
#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset_import.h"
#include "keyturn/dataset/object_list.h"
#include "layout_walk.h"
#include "pbm_image.h"

namespace keyturn::dataset {
namespace {

constexpr double kDepthUnit = 1e-4;  // metres: BigBIRD's depth images count 100 µm

// One Carmine's calibration, from the object's calibration.h5.
struct Camera {
  DepthIntrinsics depth_k;
  double depth_scale = kDepthUnit;  // metres per unit, NPi_ir_depth_scale applied
  Eigen::Matrix4d ir_from_np5;
  std::optional<DepthIntrinsics> rgb_k;  // the colour camera the masks were drawn in
  Eigen::Matrix4d rgb_from_ir = Eigen::Matrix4d::Identity();
};

// "NP3_117" → camera 3, angle 117; false unless the whole stem is of that form.
bool parseView(const std::string& stem, int& camera, int& angle) {
  if (stem.size() < 5 || stem.compare(0, 2, "NP") != 0 || stem[2] < '1' || stem[2] > '5' || stem[3] != '_') return false;
  const std::string a = stem.substr(4);
  if (a.empty() || a.size() > 3 || a.find_first_not_of("0123456789") != std::string::npos) return false;
  camera = stem[2] - '0';
  angle = std::stoi(a);
  return angle < 360;
}

bool cut(const std::string& name, const std::string& suffix, std::string& stem) {
  if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) return false;
  stem = name.substr(0, name.size() - suffix.size());
  return true;
}

DepthIntrinsics intrinsics(const H5File& f, const std::string& name) {
  const Eigen::MatrixXd k = f.matrix(name, 3, 3);
  if (!(k(0, 0) > 0) || !(k(1, 1) > 0) || k(2, 0) != 0 || k(2, 1) != 0 || k(2, 2) != 1)
    throw Error(f.path() + ": dataset \"" + name + "\" is not a camera matrix [fx 0 cx; 0 fy cy; 0 0 1]");
  return {k(0, 0), k(1, 1), k(0, 2), k(1, 2)};
}

Eigen::Matrix4d rigid(const H5File& f, const std::string& name) {
  const Eigen::Matrix4d m = f.matrix(name, 4, 4);
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  if (!m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)) || !(r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-3) ||
      !(r.determinant() > 0))
    throw Error(f.path() + ": dataset \"" + name + "\" is not a rigid transform");
  return m;
}

Camera readCamera(const H5File& cal, int i, bool with_masks) {
  const std::string np = "NP" + std::to_string(i);
  Camera c;
  c.depth_k = intrinsics(cal, np + "_depth_K");
  if (cal.has(np + "_ir_depth_scale")) {
    const double s = cal.matrix(np + "_ir_depth_scale", 1, 1)(0, 0);
    if (!(s > 0.5 && s < 2)) throw Error(cal.path() + ": " + np + "_ir_depth_scale " + std::to_string(s) + " is not near 1");
    c.depth_scale = kDepthUnit * s;
  }
  c.ir_from_np5 = rigid(cal, "H_" + np + "_ir_from_NP5");
  if (with_masks) {
    c.rgb_k = intrinsics(cal, np + "_rgb_K");
    c.rgb_from_ir = rigid(cal, "H_" + np + "_from_NP5") * c.ir_from_np5.inverse();
  }
  return c;
}

// The mask as the depth image sees it: each pixel's point projected into the colour image (the
// lens distortion NPi_rgb_d not applied: under a pixel near the centre, where the objects are).
std::vector<std::uint8_t> maskOfDepth(const DepthPixels& d, const Camera& c, const std::string& pbm) {
  const Bitmap mask = readPbm(pbm);
  const DepthIntrinsics& k = *c.rgb_k;
  std::vector<std::uint8_t> out(d.values.size(), 0);
  for (std::uint32_t v = 0; v < d.height; ++v)
    for (std::uint32_t u = 0; u < d.width; ++u) {
      const std::size_t i = std::size_t(v) * d.width + u;
      if (!d.values[i]) continue;
      const double z = d.values[i] * c.depth_scale;
      const Eigen::Vector4d p((u - c.depth_k.cx) * z / c.depth_k.fx, (v - c.depth_k.cy) * z / c.depth_k.fy, z, 1);
      const Eigen::Vector4d q = c.rgb_from_ir * p;
      if (!(q.z() > 0)) continue;
      const double ur = std::floor(k.fx * q.x() / q.z() + k.cx + 0.5), vr = std::floor(k.fy * q.y() / q.z() + k.cy + 0.5);
      if (ur >= 0 && vr >= 0 && ur < mask.width && vr < mask.height)
        out[i] = mask.black[std::size_t(vr) * mask.width + std::size_t(ur)];
    }
  return out;
}

// The camera's elevation above the table plane, from its centre in the table's frame (z along the axis).
double elevationDeg(const Eigen::Matrix4d& camera_from_table) {
  const Eigen::Vector3d centre = -camera_from_table.topLeftCorner<3, 3>().transpose() * camera_from_table.topRightCorner<3, 1>();
  return std::atan2(std::abs(centre.z()), std::hypot(centre.x(), centre.y())) * 180 / M_PI;
}

struct Object {
  std::string calibration;
  std::map<std::pair<int, int>, std::string> views, masks;  // (camera, angle) → file
  std::map<int, std::string> poses;                         // angle → NP5's pose file
};

// The layout's files by object; what is not BigBIRD's is a problem line.
std::map<std::string, Object> objectsOf(const std::string& source, std::vector<std::string>& problems) {
  std::map<std::string, Object> objects;
  for (const auto& f : layoutFiles(source, problems)) {
    const std::string& name = f.parts.back();
    std::string stem;
    int camera = 0, angle = 0;
    if (f.parts.size() < 2) {
      problems.push_back(f.path + ": not in an OBJECT folder (BigBIRD layout: OBJECT/NPi_ANGLE.h5)");
    } else if (f.parts.size() == 2) {
      Object& o = objects[f.parts[0]];
      if (name == "calibration.h5") o.calibration = f.path;
      else if (cut(name, ".h5", stem) && parseView(stem, camera, angle)) o.views[{camera, angle}] = f.path;
      else if (!cut(name, ".jpg", stem))  // the colour images: keyturn describes shape only
        problems.push_back(f.path + ": malformed name (expected NPi_ANGLE.h5, i 1 to 5, ANGLE 0 to 357, or calibration.h5)");
    } else if (f.parts.size() == 3 && f.parts[1] == "poses") {
      if (!cut(name, "_pose.h5", stem) || !parseView(stem, camera, angle))
        problems.push_back(f.path + ": malformed name (expected poses/NP5_ANGLE_pose.h5)");
      else if (camera == 5)  // the reference camera's: the one the calibration's H_NPi_ir_from_NP5 start from
        objects[f.parts[0]].poses[angle] = f.path;
    } else if (f.parts.size() == 3 && f.parts[1] == "masks") {
      if (cut(name, "_mask.pbm", stem) && parseView(stem, camera, angle)) objects[f.parts[0]].masks[{camera, angle}] = f.path;
      else problems.push_back(f.path + ": malformed name (expected masks/NPi_ANGLE_mask.pbm)");
    }  // BigBIRD's own products (clouds/, meshes/, …) are not views
  }
  return objects;
}

// The calibration of each camera the object has views of; a camera it cannot calibrate is a problem line.
std::map<int, Camera> camerasOf(const std::string& object, const Object& o, std::vector<std::string>& problems) {
  const H5File cal(o.calibration);
  std::set<int> used, masked;
  for (const auto& view : o.views) used.insert(view.first.first);
  for (const auto& mask : o.masks) masked.insert(mask.first.first);
  std::map<int, Camera> cams;
  for (int i : used) try {
      cams[i] = readCamera(cal, i, masked.count(i) > 0);
    } catch (const Error& e) {
      problems.push_back(std::string(e.what()) + " (the NP" + std::to_string(i) + " views of " + object + " not imported)");
    }
  return cams;
}

// H_table_from_reference_camera at one angle; none (and a problem line) when missing or unusable.
std::optional<Eigen::Matrix4d> poseAt(const std::string& folder, const Object& o, int angle, std::vector<std::string>& problems) {
  const auto p = o.poses.find(angle);
  try {
    if (p != o.poses.end()) return rigid(H5File(p->second), "H_table_from_reference_camera");
    problems.push_back("missing " + folder + "/poses/NP5_" + std::to_string(angle) + "_pose.h5 (the turntable's pose at " +
                       std::to_string(angle) + "°: the views at that angle not imported)");
  } catch (const Error& e) {
    problems.push_back(std::string(e.what()) + " (the views at " + std::to_string(angle) + "° not imported)");
  }
  return std::nullopt;
}

ImportedView viewOf(const std::string& cls, const std::string& object, int camera, int angle, const std::string& file,
                    const Camera& cam, const Eigen::Matrix4d& table_from_np5, const std::string& mask) {
  ImportedView v;
  v.camera_from_turntable = cam.ir_from_np5 * table_from_np5.inverse();
  v.elevation_deg = elevationDeg(*v.camera_from_turntable);
  v.key = {cls, object, "NP" + std::to_string(camera), double(angle)};
  v.file = file;
  const std::string np = "NP" + std::to_string(camera), a = std::to_string(angle);
  v.angle_note = "BigBIRD poses/NP5_" + a + "_pose.h5 (the turntable's calibration board seen by NP5) and calibration.h5 H_" +
                 np + "_ir_from_NP5" + (mask.empty() ? "" : "; mask masks/" + np + "_" + a + "_mask.pbm");
  v.read = [file, cam, mask] {
    const DepthPixels d = H5File(file).depth("depth");
    return depthImageToCloud(d.values, d.width, d.height, cam.depth_k, cam.depth_scale,
                             mask.empty() ? std::vector<std::uint8_t>{} : maskOfDepth(d, cam, mask));
  };
  return v;
}

}  // namespace

ImportPlan planBigbirdImport(const std::string& source, const std::string& categories) {
  ImportPlan plan;
  const std::map<std::string, std::string> classes = categories.empty() ? std::map<std::string, std::string>{}
                                                                         : readInstanceClasses(categories);
  for (const auto& [object, o] : objectsOf(source, plan.problems)) {
    if (o.views.empty()) continue;
    const std::string folder = (std::filesystem::path(source) / object).string();
    const std::string views = " (" + std::to_string(o.views.size()) + (o.views.size() == 1 ? " view of " : " views of ") +
                              object + " not imported)";
    const auto listed = classes.find(object);
    if (!categories.empty() && listed == classes.end()) {
      plan.problems.push_back(folder + ": not in " + categories + " (no class for instance " + object + ")" + views);
      continue;
    }
    if (o.calibration.empty()) {
      plan.problems.push_back("missing " + folder + "/calibration.h5" + views);
      continue;
    }
    std::map<int, Camera> cams;
    try {
      cams = camerasOf(object, o, plan.problems);
    } catch (const Error& e) {  // calibration.h5 itself unreadable
      plan.problems.push_back(e.what() + views);
      continue;
    }
    std::map<int, std::optional<Eigen::Matrix4d>> table_from_np5;  // by angle, read once
    for (const auto& [camera_angle, file] : o.views) {
      const auto [camera, angle] = camera_angle;
      if (!cams.count(camera)) continue;
      if (!table_from_np5.count(angle)) table_from_np5[angle] = poseAt(folder, o, angle, plan.problems);
      if (!table_from_np5[angle]) continue;
      const auto mask = o.masks.find(camera_angle);
      plan.views.push_back(viewOf(listed == classes.end() ? object : listed->second, object, camera, angle, file,
                                  cams.at(camera), *table_from_np5[angle], mask == o.masks.end() ? "" : mask->second));
    }
  }
  return plan;
}

}  // namespace keyturn::dataset
