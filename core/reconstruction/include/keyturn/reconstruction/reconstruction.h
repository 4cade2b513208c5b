#pragma once
// From posed views of one object to its model: the views' points (filtered as describe filters
// them), their poses refined (registration.h: free or turntable model), the fused cloud and its
// surface (surface.h: Poisson, or TSDF for depth frames), with what changed and how well the views agree, per view.
#include <optional>
#include <string>
#include <vector>

#include "keyturn/core/filter.h"
#include "keyturn/reconstruction/posed_views.h"
#include "keyturn/reconstruction/registration.h"
#include "keyturn/reconstruction/surface.h"

namespace keyturn::reconstruction {

enum class ModelChoice { Auto, Free, Turntable };  // Auto: Turntable when every view is a turntable view
// Auto: TSDF when every view is an organized depth frame (depthFrameFromCloud), else Poisson.
enum class SurfaceChoice { Auto, Poisson, Tsdf };

// describe's filter, but the band removed with the support is 3 σ of each frame's own table noise
// (within 1–8 mm) instead of a fixed 8 mm: a thin object keeps its lower half.
inline FilterOptions reconstructionFilterOptions() {
  FilterOptions f;
  f.plane_band_sigmas = 3.f;
  return f;
}

struct ReconstructionOptions {
  RegistrationOptions registration;
  ModelChoice model = ModelChoice::Auto;
  bool filter = true;
  FilterOptions filter_options = reconstructionFilterOptions();
  double fuse_voxel_m = 0;  // 0: half the registration voxel
  SurfaceChoice surface = SurfaceChoice::Auto;
  PoissonOptions poisson;  // its cleanup is `cleanup` below
  // truncation 0: 1.5 σ of the sensor's noise, measured on the support plane the views stood on
  // (the band the filter removed with it is plane_band_sigmas σ; median over views), or 4 voxels
  // without one; voxel 0: half the truncation, at most the fused cloud's voxel. (Chosen on the
  // simulated mug and bowl through both cameras: docs/reconstruction.md, "TSDF or Poisson".)
  TsdfOptions tsdf = [] {
    TsdfOptions t;
    t.voxel_m = 0;
    t.truncation_m = 0;
    return t;
  }();
  SurfaceCleanup cleanup = [] {
    SurfaceCleanup c;
    c.max_triangles = 50000;  // enough for 1 mm detail on a 25 cm object; the simulated cameras render it quickly
    return c;
  }();
  double surface_reach_voxels = 4;  // the surface's vertices kept within this many registration voxels of the points
  // When most views stood on a support (the filter found and removed it): the object's foot is closed
  // on it (points on the support under the lowest fused points, facing down) and nothing is kept below it.
  bool close_on_support = true;
  // Turntable views: a view whose filter kept the support (a flat object) has it cut with the plane
  // its rig camera's other views found (the platter is one plane in every view of one camera).
  bool support_from_rig_camera = true;
  // Evaluation against known truth (docs/reconstruction.md's tables), all optional.
  std::vector<Eigen::Matrix4d> reference_poses;  // one per view, the true world_from_view (compared through the reference view)
  std::optional<Mesh> reference_surface;
  double fscore_tau_m = 0.001;
};

struct ViewOutcome {
  std::string file;
  std::size_t points = 0;
  double residual_before_m = 0, residual_after_m = 0, overlap_before = 0, overlap_after = 0;
  PoseDifference change;                          // refined against initial
  bool support_from_rig_camera = false;           // its support cut with its rig camera's plane (its filter kept it)
  std::optional<PoseDifference> error_before, error_after;  // against the reference poses
};

struct AxisReport {
  std::string camera;  // the elevation
  ImpliedAxis initial, refined;  // from the initial (calibrated) and the refined poses
  std::optional<double> levelled_deg;  // the tilt the support plane corrected, when it held this camera's tilt
};

struct Reconstruction {
  std::vector<PosedView> views;  // poses refined
  std::vector<Eigen::Matrix4d> initial_poses;
  std::vector<ViewOutcome> outcomes;
  std::vector<RegistrationPair> pairs;
  std::vector<AxisReport> axes;
  PoseModel model = PoseModel::Free;
  bool refined = true;
  bool turns_kept = false;  // the rig cameras' turns about the axis kept as calibrated (registration.h)
  double voxel_m = 0;
  OrientedPoints cloud;
  Mesh mesh;
  SurfaceChoice surface = SurfaceChoice::Poisson;  // how `mesh` was made
  std::string surface_note;                          // why Auto chose Poisson, when it did
  double tsdf_voxel_m = 0, tsdf_truncation_m = 0;    // the TSDF's, when it made the surface
  std::optional<Eigen::Vector4d> support;  // the support plane in the common frame (median of the views'), when found
  double support_band_m = 0;               // the height above it the filter removed (median over views)
  std::size_t support_points = 0;          // points added on it to close the object's foot
  // Against the reference surface, when given: the fused points' distances (initial and refined
  // poses) and the mesh's F-score.
  std::optional<double> cloud_distance_before_m, cloud_distance_after_m;
  std::optional<SurfaceComparison> mesh_comparison;
  std::vector<std::pair<std::string, double>> stage_seconds;
};

struct ReconstructionProgress {
  RegistrationProgress stages;                                 // bars of the long stages
  std::function<void(const std::string& line)> line = [](const std::string&) {};  // a line per stage
};

// Throws keyturn::Error (unreadable view, too few points, NoOverlapError).
Reconstruction reconstruct(std::vector<PosedView> views, const ReconstructionOptions& options,
                           const ReconstructionProgress& progress = ReconstructionProgress());

// DIR/cloud.ply, DIR/mesh.ply, DIR/poses.txt and DIR/report.json (created, written durably).
void writeReconstruction(const std::string& dir, const Reconstruction& r, const std::string& input);
std::string reconstructionJson(const Reconstruction& r, const std::string& input);
std::string reconstructionSummary(const Reconstruction& r);

}  // namespace keyturn::reconstruction
