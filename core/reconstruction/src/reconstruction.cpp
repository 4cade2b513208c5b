#include "keyturn/reconstruction/reconstruction.h"

#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <iomanip>
#include <limits>
#include <sstream>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/median.h"
#include "keyturn/core/parallel_for.h"
#include "keyturn/core/string_format.h"
#include "keyturn/reconstruction/support.h"

namespace keyturn::reconstruction {

namespace {

using Clock = std::chrono::steady_clock;

// `digits` significant digits, "nan" for a missing value.
std::string formatNumber(double x, int digits) {
  std::string out;
  appendFormat(out, "%.*g", digits, x);
  return out;
}

class StageClock {
 public:
  StageClock(Reconstruction& r, const ReconstructionProgress& p) : r_(r), p_(p) {}
  void done(const std::string& stage, const std::string& detail) {
    const double s = std::chrono::duration<double>(Clock::now() - start_).count();
    r_.stage_seconds.emplace_back(stage, s);
    std::ostringstream line;
    line << stage << ": " << detail << " (" << std::fixed << std::setprecision(1) << s << " s)";
    p_.line(line.str());
    start_ = Clock::now();
  }

 private:
  Reconstruction& r_;
  const ReconstructionProgress& p_;
  Clock::time_point start_ = Clock::now();
};

std::vector<Eigen::Vector3f> validPoints(const Cloud& c) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(c.size());
  for (const auto& p : c.points)
    if (Cloud::isValid(p)) out.push_back(p);
  return out;
}

OrientedPoints fuse(const std::vector<std::vector<Eigen::Vector3f>>& points, const std::vector<Eigen::Matrix4d>& poses,
                    double voxel) {
  std::vector<FuseView> fv;
  for (std::size_t i = 0; i < points.size(); ++i) fv.push_back({&points[i], poses[i]});
  return fuseViews(fv, FuseOptions{voxel});
}

// The TSDF's truncation and voxel where the options leave them to the data (reconstruction.h);
// `from` says where the truncation came from.
TsdfOptions tsdfOptionsFor(const ReconstructionOptions& options, const std::vector<FilterReport>& filtered,
                           double fuse_voxel, std::string& from) {
  TsdfOptions tsdf = options.tsdf;
  if (tsdf.truncation_m <= 0) {
    std::vector<double> sigmas;  // each frame's table noise: its band is plane_band_sigmas σ
    const float band_sigmas = options.filter_options.plane_band_sigmas;
    for (const auto& f : filtered)
      if (band_sigmas > 0 && f.plane_found && f.plane_band > 0) sigmas.push_back(f.plane_band / band_sigmas);
    const double sigma = upperMedian(sigmas);
    if (std::isfinite(sigma)) {
      tsdf.truncation_m = 1.5 * sigma;
      from = " (1.5 σ of the support's noise)";
    } else {
      tsdf.truncation_m = 4 * (tsdf.voxel_m > 0 ? tsdf.voxel_m : fuse_voxel);
      from = " (4 voxels: no support to measure the noise on)";
    }
  }
  if (tsdf.voxel_m <= 0) tsdf.voxel_m = std::min(fuse_voxel, tsdf.truncation_m / 2);
  tsdf.truncation_m = std::max(tsdf.truncation_m, 2 * tsdf.voxel_m);
  return tsdf;
}

// Each rig camera (a dataset's elevation) numbered in the order its first view comes.
std::map<std::string, int> rigCameras(const std::vector<PosedView>& views) {
  std::map<std::string, int> cameras;
  for (const auto& v : views) cameras.emplace(v.elevation, int(cameras.size()));
  return cameras;
}

// A turntable's platter is one plane in every view of one rig camera (it turns within that plane).
// A view whose filter kept it (a flat object, the table's far side and the floor outnumbering it:
// "the rest lies behind it") has it cut with the plane its camera's other views found, and is
// filtered again without the plane step. Returns those views.
std::vector<std::size_t> supportFromRigCamera(const std::vector<PosedView>& views, const ReconstructionOptions& options,
                                 std::vector<FilterReport>& filtered, std::vector<std::vector<Eigen::Vector3f>>& points,
                                 std::vector<std::optional<DepthFrame>>& frames, std::vector<std::string>& not_a_frame) {
  if (!options.support_from_rig_camera || !options.filter || !options.filter_options.remove_plane ||
      !std::all_of(views.begin(), views.end(), [](const auto& v) { return v.turntable; }))
    return {};
  const auto cameras = rigCameras(views);
  std::vector<int> rig(views.size());
  std::vector<SupportView> sv;
  for (std::size_t i = 0; i < views.size(); ++i) {
    rig[i] = cameras.at(views[i].elevation);
    sv.push_back({filtered[i].plane_found, filtered[i].plane, filtered[i].plane_band, views[i].world_from_view});
  }
  const auto planes = rigCameraPlanes(sv, rig);
  std::vector<double> band(planes.size());  // each camera's median band, for the views given its plane
  for (std::size_t k = 0; k < planes.size(); ++k) {
    std::vector<double> b;
    for (std::size_t i = 0; i < views.size(); ++i)
      if (rig[i] == int(k) && filtered[i].plane_found) b.push_back(filtered[i].plane_band);
    band[k] = upperMedian(b);
  }
  std::vector<std::size_t> redo;
  for (std::size_t i = 0; i < views.size(); ++i)
    if (!filtered[i].plane_found && planes[rig[i]]) redo.push_back(i);
  parallelFor(redo.size(), 0, [&](std::size_t j) {
    const std::size_t i = redo[j];
    const Eigen::Vector4f plane = planes[rig[i]]->cast<float>();
    const Cloud c = loadCloud(views[i].file);
    Cloud cut = c;
    for (auto& p : cut.points)  // the band above the plane and everything behind it, as the plane step removes them
      if (Cloud::isValid(p) && plane.head<3>().dot(p) + plane[3] < options.filter_options.plane_distance)
        p = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
    FilterOptions without_plane = options.filter_options;
    without_plane.remove_plane = false;
    FilterReport report;
    const Cloud f = filterCloud(cut, without_plane, &report);
    points[i] = validPoints(f);
    if (points[i].size() < 100)
      throw Error(views[i].file + ": " + std::to_string(points[i].size()) +
                  " valid points after its rig camera's support plane was cut, a view needs 100");
    report.plane_found = true, report.plane = plane, report.plane_band = float(band[rig[i]]);
    filtered[i] = report;
    if (options.surface != SurfaceChoice::Poisson) frames[i] = depthFrameFromCloud(c, f, views[i].world_from_view, &not_a_frame[i]);
  });
  return redo;
}

}  // namespace

Reconstruction reconstruct(std::vector<PosedView> views, const ReconstructionOptions& options,
                           const ReconstructionProgress& progress) {
  Reconstruction r;
  StageClock clock(r, progress);
  if (views.size() < 2) throw Error("a reconstruction needs at least two views, got " + std::to_string(views.size()));
  if (!options.reference_poses.empty() && options.reference_poses.size() != views.size())
    throw Error("the reference poses are " + std::to_string(options.reference_poses.size()) + ", the views " +
                std::to_string(views.size()));

  // Views: read and filtered as describe filters them (a frame's support plane and background go).
  std::vector<std::vector<Eigen::Vector3f>> points(views.size());
  std::vector<FilterReport> filtered(views.size());
  // Depth frames for a TSDF surface, when one may be made (poses set after registration).
  std::vector<std::optional<DepthFrame>> frames(views.size());
  std::vector<std::string> not_a_frame(views.size());
  progress.stages.begin("reading views", views.size());
  parallelFor(views.size(), 0, [&](std::size_t i) {
    const Cloud c = loadCloud(views[i].file);
    const Cloud f = options.filter ? filterCloud(c, options.filter_options, &filtered[i]) : c;
    points[i] = validPoints(f);
    if (points[i].size() < 100)
      throw Error(views[i].file + ": " + std::to_string(points[i].size()) +
                  " valid points after filtering, a view needs 100");
    if (options.surface != SurfaceChoice::Poisson)
      frames[i] = depthFrameFromCloud(c, f, views[i].world_from_view, &not_a_frame[i]);
    progress.stages.step();
  });
  progress.stages.end();
  const auto from_rig = supportFromRigCamera(views, options, filtered, points, frames, not_a_frame);
  const auto first_not_a_frame = std::find(frames.begin(), frames.end(), std::nullopt) - frames.begin();
  r.surface = SurfaceChoice::Tsdf;
  if (options.surface == SurfaceChoice::Poisson) {
    r.surface = SurfaceChoice::Poisson;
  } else if (first_not_a_frame < std::ptrdiff_t(views.size())) {
    const std::string why = views[first_not_a_frame].file + ": " + not_a_frame[first_not_a_frame];
    if (options.surface == SurfaceChoice::Tsdf)
      throw Error(why + "; a TSDF surface needs every view to be an organized depth frame (a Poisson surface does not)");
    r.surface = SurfaceChoice::Poisson;
    r.surface_note = "Poisson, not TSDF: " + why;
    frames.clear();
  }
  std::size_t total = 0;
  for (const auto& p : points) total += p.size();
  clock.done("views", std::to_string(views.size()) + " views, " + std::to_string(total) + " points" +
                          (options.filter ? " after filtering" : ""));
  if (!r.surface_note.empty()) progress.line(r.surface_note);
  if (!from_rig.empty())
    progress.line(std::to_string(from_rig.size()) + " view" + (from_rig.size() == 1 ? "" : "s") +
                  ": the support cut with the plane their rig camera's other views found (their own filter kept it)");

  const bool all_turntable = std::all_of(views.begin(), views.end(), [](const auto& v) { return v.turntable; });
  if (options.model == ModelChoice::Turntable && !all_turntable)
    throw Error("the turntable model needs every view's turntable angle: a calibrated dataset's views");
  r.model = options.model == ModelChoice::Free ? PoseModel::Free
            : all_turntable                    ? PoseModel::Turntable
                                               : PoseModel::Free;
  const auto cameras = rigCameras(views);
  std::vector<RegistrationView> rv(views.size());
  for (std::size_t i = 0; i < views.size(); ++i)
    rv[i] = {views[i].file, points[i], views[i].world_from_view, cameras.at(views[i].elevation)};
  RegistrationOptions ro = options.registration;
  ro.model = r.model;
  std::optional<RigLevelling> levelling;
  if (r.model == PoseModel::Turntable && ro.refine && ro.level_on_support && options.filter) {
    std::vector<SupportView> sv;
    std::vector<int> rig_camera;
    for (std::size_t i = 0; i < views.size(); ++i) {
      sv.push_back({filtered[i].plane_found, filtered[i].plane, filtered[i].plane_band, rv[i].world_from_view});
      rig_camera.push_back(rv[i].rig_camera);
    }
    levelling = levelRigOnSupport(sv, rig_camera);
    for (std::size_t i = 0; i < views.size(); ++i)
      if (const auto& plane = levelling->camera_plane[rv[i].rig_camera]) {
        rv[i].support = *plane;
        rv[i].level = rv[i].world_from_view.inverse() * levelling->world_from_view[i];
      }
  }
  const RegistrationResult reg = registerViews(rv, ro, progress.stages);
  r.refined = ro.refine;
  r.turns_kept = reg.turns_kept;
  r.voxel_m = reg.voxel_m;
  r.pairs = reg.pairs;
  for (auto& v : rv) v.points.clear(), v.points.shrink_to_fit();
  for (const auto& v : views) r.initial_poses.push_back(v.world_from_view);
  {
    std::ostringstream d;
    d << (ro.refine ? "refined (" + std::string(poseModelName(r.model)) + " poses), " : "not refined, ")
      << reg.pairs.size() << " overlapping pairs, views to each other (median) "
      << formatNumber(upperMedian(reg.residual_before_m) * 1000, 3) << " mm → "
      << formatNumber(upperMedian(reg.residual_after_m) * 1000, 3) << " mm";
    clock.done("registration", d.str());
  }

  for (std::size_t i = 0; i < views.size(); ++i) {
    ViewOutcome o;
    o.file = views[i].file;
    o.points = points[i].size();
    o.residual_before_m = reg.residual_before_m[i];
    o.residual_after_m = reg.residual_after_m[i];
    o.overlap_before = reg.overlap_before[i];
    o.overlap_after = reg.overlap_after[i];
    o.change = poseDifference(views[i].world_from_view, reg.world_from_view[i]);
    o.support_from_rig_camera = std::find(from_rig.begin(), from_rig.end(), i) != from_rig.end();
    if (!options.reference_poses.empty()) {
      // Both sets in the reference's frame through the reference view (the gauge registration
      // keeps): the identity when that view's pose was right, as in a perturbation test.
      const int ref = ro.reference;
      const Eigen::Matrix4d g0 = options.reference_poses[ref] * r.initial_poses[ref].inverse();
      const Eigen::Matrix4d g1 = options.reference_poses[ref] * reg.world_from_view[ref].inverse();
      o.error_before = poseDifference(options.reference_poses[i], g0 * r.initial_poses[i]);
      o.error_after = poseDifference(options.reference_poses[i], g1 * reg.world_from_view[i]);
    }
    r.outcomes.push_back(o);
    views[i].world_from_view = reg.world_from_view[i];
  }
  if (all_turntable) {
    for (const auto& [camera, index] : cameras) {
      std::vector<Eigen::Matrix4d> before, after;
      for (std::size_t i = 0; i < views.size(); ++i)
        if (views[i].elevation == camera) before.push_back(r.initial_poses[i]), after.push_back(views[i].world_from_view);
      try {
        AxisReport a{camera, impliedAxis(before), impliedAxis(after), std::nullopt};
        if (levelling && levelling->camera_plane[index]) a.levelled_deg = levelling->tilt_deg[index];
        r.axes.push_back(a);
      } catch (const Error&) {  // one camera's views span less than 10°: it implies no axis
      }
    }
  }

  const double fuse_voxel = options.fuse_voxel_m > 0 ? options.fuse_voxel_m : reg.voxel_m / 2;
  r.cloud = fuse(points, reg.world_from_view, fuse_voxel);
  SurfaceCleanup cleanup = options.cleanup;
  if (options.surface_reach_voxels > 0 && cleanup.max_distance_m <= 0)
    cleanup.max_distance_m = options.surface_reach_voxels * reg.voxel_m;
  OrientedPoints surface_points = r.cloud;
  if (options.close_on_support) {
    std::vector<SupportView> sv;
    for (std::size_t i = 0; i < views.size(); ++i)
      sv.push_back({filtered[i].plane_found, filtered[i].plane, filtered[i].plane_band, reg.world_from_view[i]});
    if (const auto support = commonSupport(sv)) {
      r.support = support->plane;
      r.support_band_m = support->band_m;
      cleanup.floor = support->plane;
      if (r.surface == SurfaceChoice::Poisson) {  // a TSDF leaves open what no frame saw
        const auto foot = footOnSupport(r.cloud, *support, 2 * fuse_voxel);
        r.support_points = foot.points.size();
        surface_points.points.insert(surface_points.points.end(), foot.points.begin(), foot.points.end());
        surface_points.normals.insert(surface_points.normals.end(), foot.normals.begin(), foot.normals.end());
      }
    }
  }
  clock.done("fusion", std::to_string(r.cloud.points.size()) + " points at " + formatNumber(fuse_voxel * 1000, 3) +
                           " mm" + (r.support_points ? ", " + std::to_string(r.support_points) + " closing the foot on the support" : ""));
  std::string surface_line;
  if (r.surface == SurfaceChoice::Tsdf) {
    std::vector<DepthFrame> posed;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      posed.push_back(std::move(*frames[i]));
      posed.back().world_from_view = reg.world_from_view[i];
    }
    frames.clear();
    std::string truncation_from;
    TsdfOptions tsdf = tsdfOptionsFor(options, filtered, fuse_voxel, truncation_from);
    tsdf.cleanup = cleanup;
    r.tsdf_voxel_m = tsdf.voxel_m, r.tsdf_truncation_m = tsdf.truncation_m;
    r.mesh = tsdfSurface(posed, r.cloud, tsdf);
    surface_line = "TSDF at " + formatNumber(tsdf.voxel_m * 1000, 3) + " mm, truncated at " +
                   formatNumber(tsdf.truncation_m * 1000, 3) + " mm" + truncation_from;
  } else {
    PoissonOptions poisson = options.poisson;
    poisson.cleanup = cleanup;
    r.mesh = poissonSurface(surface_points, poisson);
    surface_line = "Poisson depth " + std::to_string(options.poisson.depth);
  }
  clock.done("surface", surface_line + ", " + std::to_string(r.mesh.vertices.size()) + " vertices, " +
                            std::to_string(r.mesh.triangles.size()) + " triangles");
  r.views = std::move(views);

  if (options.reference_surface) {
    // In the reference's frame through the reference view, as the pose errors are: a mis-set axis
    // moves every view, the reference's too, and the model's own frame with it.
    Eigen::Matrix4d g0 = Eigen::Matrix4d::Identity(), g1 = g0;
    if (!options.reference_poses.empty()) {
      g0 = options.reference_poses[ro.reference] * r.initial_poses[ro.reference].inverse();
      g1 = options.reference_poses[ro.reference] * reg.world_from_view[ro.reference].inverse();
    }
    const auto moved = [](std::vector<Eigen::Vector3f> points, const Eigen::Matrix4d& g) {
      const Eigen::Matrix4f gf = g.cast<float>();
      for (auto& p : points) p = (gf * p.homogeneous()).head<3>();
      return points;
    };
    const auto before = fuse(points, r.initial_poses, fuse_voxel);
    r.cloud_distance_before_m = upperMedian(distancesToMesh(moved(before.points, g0), *options.reference_surface));
    r.cloud_distance_after_m = upperMedian(distancesToMesh(moved(r.cloud.points, g1), *options.reference_surface));
    Mesh surface = r.mesh;
    surface.vertices = moved(surface.vertices, g1);
    r.mesh_comparison = compareSurfaces(surface, *options.reference_surface, options.fscore_tau_m);
    clock.done("evaluation", "fused cloud to the reference surface " +
                                 formatNumber(*r.cloud_distance_before_m * 1000, 3) + " mm → " +
                                 formatNumber(*r.cloud_distance_after_m * 1000, 3) + " mm (median), mesh F-score at " +
                                 formatNumber(options.fscore_tau_m * 1000, 3) + " mm " +
                                 formatNumber(r.mesh_comparison->fscore, 3));
  }
  return r;
}

std::string reconstructionJson(const Reconstruction& r, const std::string& input) {
  using nlohmann::json;
  auto vec = [](const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); };
  auto diff = [](const PoseDifference& d) { return json{{"rotation_deg", d.rotation_deg}, {"translation_m", d.translation_m}}; };
  auto num = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  json j;
  j["input"] = input;
  j["model"] = poseModelName(r.model);
  j["refined"] = r.refined;
  j["turns_about_axis_kept"] = r.turns_kept;
  j["voxel_m"] = r.voxel_m;
  std::vector<double> before, after, err_r0, err_t0, err_r1, err_t1;
  for (const auto& o : r.outcomes) {
    json v{{"file", o.file},
           {"points", o.points},
           {"residual_before_m", num(o.residual_before_m)},
           {"residual_after_m", num(o.residual_after_m)},
           {"overlap_before", o.overlap_before},
           {"overlap_after", o.overlap_after},
           {"pose_change", diff(o.change)},
           {"support_from_rig_camera", o.support_from_rig_camera}};
    before.push_back(o.residual_before_m), after.push_back(o.residual_after_m);
    if (o.error_before) {
      v["pose_error_before"] = diff(*o.error_before), v["pose_error_after"] = diff(*o.error_after);
      err_r0.push_back(o.error_before->rotation_deg), err_t0.push_back(o.error_before->translation_m);
      err_r1.push_back(o.error_after->rotation_deg), err_t1.push_back(o.error_after->translation_m);
    }
    j["views"].push_back(v);
  }
  j["residual_median_before_m"] = num(upperMedian(before));
  j["residual_median_after_m"] = num(upperMedian(after));
  if (!err_r0.empty()) {
    auto mx = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
    j["pose_error"] = {{"before", {{"rotation_deg_median", upperMedian(err_r0)}, {"rotation_deg_max", mx(err_r0)},
                                   {"translation_m_median", upperMedian(err_t0)}, {"translation_m_max", mx(err_t0)}}},
                       {"after", {{"rotation_deg_median", upperMedian(err_r1)}, {"rotation_deg_max", mx(err_r1)},
                                  {"translation_m_median", upperMedian(err_t1)}, {"translation_m_max", mx(err_t1)}}}};
  }
  for (const auto& p : r.pairs)
    j["pairs"].push_back({{"a", p.a}, {"b", p.b}, {"overlap", p.overlap}, {"fitness", p.fitness}, {"pruned", p.pruned}});
  for (const auto& a : r.axes)
    j["axes"].push_back({{"camera", a.camera},
                         {"calibrated", {{"direction", vec(a.initial.direction)}, {"point_m", vec(a.initial.point)}}},
                         {"refined", {{"direction", vec(a.refined.direction)}, {"point_m", vec(a.refined.point)}}},
                         {"angle_between_deg", std::acos(std::clamp(a.initial.direction.dot(a.refined.direction), -1.0, 1.0)) * 180 / M_PI},
                         {"levelled_by_support_deg", a.levelled_deg ? nlohmann::json(*a.levelled_deg) : nlohmann::json()}});
  if (r.support)
    j["support"] = {{"plane", {(*r.support)[0], (*r.support)[1], (*r.support)[2], (*r.support)[3]}},
                    {"band_m", r.support_band_m},
                    {"foot_points", r.support_points}};
  j["cloud_points"] = r.cloud.points.size();
  j["mesh"] = {{"method", r.surface == SurfaceChoice::Tsdf ? "tsdf" : "poisson"},
               {"vertices", r.mesh.vertices.size()},
               {"triangles", r.mesh.triangles.size()}};
  if (!r.surface_note.empty()) j["mesh"]["note"] = r.surface_note;
  if (r.surface == SurfaceChoice::Tsdf) j["mesh"]["tsdf_voxel_m"] = r.tsdf_voxel_m, j["mesh"]["tsdf_truncation_m"] = r.tsdf_truncation_m;
  if (r.cloud_distance_after_m) {
    j["reference_surface"] = {{"cloud_distance_median_before_m", *r.cloud_distance_before_m},
                              {"cloud_distance_median_after_m", *r.cloud_distance_after_m},
                              {"mesh_tau_m", r.mesh_comparison->tau_m},
                              {"mesh_precision", r.mesh_comparison->precision},
                              {"mesh_recall", r.mesh_comparison->recall},
                              {"mesh_fscore", r.mesh_comparison->fscore}};
  }
  for (const auto& [stage, s] : r.stage_seconds) j["seconds"][stage] = s;
  return j.dump(2) + "\n";
}

std::string reconstructionSummary(const Reconstruction& r) {
  std::vector<double> before, after, change_r, change_t;
  for (const auto& o : r.outcomes) {
    before.push_back(o.residual_before_m), after.push_back(o.residual_after_m);
    change_r.push_back(o.change.rotation_deg), change_t.push_back(o.change.translation_m);
  }
  std::ostringstream s;
  s << r.outcomes.size() << " views, " << poseModelName(r.model) << " poses" << (r.refined ? " refined" : " kept")
    << ": views to each other " << formatNumber(upperMedian(before) * 1000, 3) << " mm → "
    << formatNumber(upperMedian(after) * 1000, 3) << " mm (median point-to-plane); pose change median "
    << formatNumber(upperMedian(change_r), 3) << "° / " << formatNumber(upperMedian(change_t) * 1000, 3) << " mm\n";
  std::vector<double> e_r, e_t;
  for (const auto& o : r.outcomes)
    if (o.error_after) e_r.push_back(o.error_after->rotation_deg), e_t.push_back(o.error_after->translation_m);
  if (!e_r.empty())
    s << "pose error against the reference: median " << formatNumber(upperMedian(e_r), 3) << "° / "
      << formatNumber(upperMedian(e_t) * 1000, 3) << " mm, max " << formatNumber(*std::max_element(e_r.begin(), e_r.end()), 3)
      << "° / " << formatNumber(*std::max_element(e_t.begin(), e_t.end()) * 1000, 3) << " mm\n";
  for (const auto& a : r.axes)
    s << "axis (" << (a.camera.empty() ? "camera" : a.camera) << ", camera frame): calibrated ["
      << formatNumber(a.initial.direction.x(), 4) << ", " << formatNumber(a.initial.direction.y(), 4) << ", "
      << formatNumber(a.initial.direction.z(), 4) << "], refined [" << formatNumber(a.refined.direction.x(), 4) << ", "
      << formatNumber(a.refined.direction.y(), 4) << ", " << formatNumber(a.refined.direction.z(), 4) << "], "
      << formatNumber(std::acos(std::clamp(a.initial.direction.dot(a.refined.direction), -1.0, 1.0)) * 180 / M_PI, 3)
      << "° apart; point moved " << formatNumber((a.initial.point - a.refined.point).norm() * 1000, 3) << " mm"
      << (a.levelled_deg ? "; tilt held by the support plane (levelled " + formatNumber(*a.levelled_deg, 3) + "°)" : "")
      << "\n";
  if (r.turns_kept)
    s << "the cameras' turns about the axis kept as calibrated: the object does not fix them (a body of revolution)\n";
  if (r.cloud_distance_after_m)
    s << "reference surface: fused cloud " << formatNumber(*r.cloud_distance_before_m * 1000, 3) << " mm → "
      << formatNumber(*r.cloud_distance_after_m * 1000, 3) << " mm (median), mesh F-score at "
      << formatNumber(r.mesh_comparison->tau_m * 1000, 3) << " mm " << formatNumber(r.mesh_comparison->fscore, 3)
      << "\n";
  return s.str();
}

void writeReconstruction(const std::string& dir, const Reconstruction& r, const std::string& input) {
  std::filesystem::create_directories(dir);
  savePointsPly(dir + "/cloud.ply", r.cloud);
  saveMeshPly(dir + "/mesh.ply", r.mesh);
  std::vector<std::string> files;
  std::vector<Eigen::Matrix4d> poses;
  for (const auto& v : r.views) files.push_back(v.file), poses.push_back(v.world_from_view);
  writeFileDurably(dir + "/poses.txt", poseListText(files, poses));
  writeFileDurably(dir + "/report.json", reconstructionJson(r, input));
}

}  // namespace keyturn::reconstruction
