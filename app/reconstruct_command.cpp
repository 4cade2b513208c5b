// keyturn reconstruct: the views of one object (a calibrated dataset, or a pose file) joined into
// one model: refined poses, the fused cloud, a Poisson surface and a report. The work is
// keyturn_reconstruction's (docs/reconstruction.md); this parses, calls and prints.
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "keyturn/core/pose_list.h"
#include "keyturn/core/string_format.h"
#include "keyturn/reconstruction/reconstruction.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct ReconstructArgs {
  std::string input, out, pose_format = "auto", poses_file, views, object, elevations, model = "auto", surface = "auto";
  std::string reference_poses, reference_mesh, perturb, misset_axis;
  unsigned seed = 1;
  bool no_refine = false, no_filter = false, free_tilt = false, quiet = false;
  PoseReadOptions poses;
  reconstruction::ReconstructionOptions options;
};

reconstruction::ModelChoice parseModel(const std::string& m) {
  if (m == "auto") return reconstruction::ModelChoice::Auto;
  if (m == "free") return reconstruction::ModelChoice::Free;
  if (m == "turntable") return reconstruction::ModelChoice::Turntable;
  throw Error("--model: '" + m + "' is not auto, free or turntable");
}

reconstruction::SurfaceChoice parseSurface(const std::string& m) {
  if (m == "auto") return reconstruction::SurfaceChoice::Auto;
  if (m == "poisson") return reconstruction::SurfaceChoice::Poisson;
  if (m == "tsdf") return reconstruction::SurfaceChoice::Tsdf;
  throw Error("--surface: '" + m + "' is not auto, poisson or tsdf");
}

int runReconstruct(ReconstructArgs a) {
  a.poses.format = parsePoseFormat(a.pose_format);
  a.poses.views = a.views;
  reconstruction::ViewSelection selection;
  selection.object = a.object;
  for (const auto& e : a.elevations.empty() ? std::vector<double>{} : parseNumberList(a.elevations, "--elevations")) {
    std::string text;
    appendFormat(text, "%g", e);
    selection.elevations.push_back(text);
  }
  const std::string source = a.poses_file.empty() ? a.input : a.poses_file;
  std::vector<reconstruction::PosedView> views;
  try {
    views = reconstruction::posedViews(source, a.poses, selection);
  } catch (const MissingViewListError& e) {
    throw Error(std::string(e.what()) + " (--views LIST)");
  } catch (const reconstruction::SeveralObjectsError& e) {
    throw Error(std::string(e.what()) + " with --object CLASS/INSTANCE");
  }
  if (!a.poses_file.empty() && std::filesystem::is_directory(a.input))
    for (auto& v : views)  // the pose file's views found in INPUT when not where the file says
      if (!std::filesystem::exists(v.file)) v.file = (std::filesystem::path(a.input) / std::filesystem::path(v.file).filename()).string();

  auto& o = a.options;
  o.model = parseModel(a.model);
  o.surface = parseSurface(a.surface);
  o.registration.refine = !a.no_refine;
  o.filter = !a.no_filter;
  if (!a.reference_poses.empty()) {
    PoseReadOptions ref;
    for (const auto& e : readPoses(a.reference_poses, ref)) o.reference_poses.push_back(e.world_from_view);
  }
  if (!a.reference_mesh.empty()) o.reference_surface = reconstruction::loadMesh(a.reference_mesh);
  o.registration.level_on_support = !a.free_tilt;
  const auto degreesAndMillimetres = [](const std::string& text, const char* option) {
    const auto p = parseNumberList(text, option);
    if (p.size() != 2 || p[0] < 0 || p[1] < 0) throw Error(std::string(option) + ": '" + text + "' is not DEGREES,MILLIMETRES");
    return p;
  };
  if (!a.perturb.empty()) {
    const auto p = degreesAndMillimetres(a.perturb, "--perturb");
    std::vector<Eigen::Matrix4d> poses;
    for (const auto& v : views) poses.push_back(v.world_from_view);
    poses = reconstruction::perturbPoses(poses, p[0], p[1] / 1000.0, a.seed);
    for (std::size_t i = 0; i < views.size(); ++i) views[i].world_from_view = poses[i];
  }
  if (!a.misset_axis.empty()) {
    const auto p = degreesAndMillimetres(a.misset_axis, "--misset-axis");
    reconstruction::missetAxis(views, p[0], p[1] / 1000.0, a.seed);
  }

  std::unique_ptr<Progress> bar;
  reconstruction::ReconstructionProgress progress;
  progress.stages = {[&](const std::string& stage, std::size_t n) { bar = std::make_unique<Progress>(stage, n, !a.quiet); },
                     [&] { bar->advance(); }, [&] { bar->finish(); }};
  progress.line = [&](const std::string& line) {
    if (!a.quiet) std::cerr << line << '\n';
  };
  const auto r = reconstruction::reconstruct(std::move(views), o, progress);
  reconstruction::writeReconstruction(a.out, r, a.input);
  std::cout << reconstruction::reconstructionSummary(r) << "Written: " << a.out
            << "/{cloud.ply, mesh.ply, poses.txt, report.json}\n";
  return 0;
}

}  // namespace

Command addReconstructCommand(CLI::App& app) {
  auto a = std::make_shared<ReconstructArgs>();
  auto* cmd = app.add_subcommand("reconstruct", "Join posed views of one object into its model: refined poses, fused cloud, surface");
  cmd->add_option("input", a->input, "A calibrated keyturn dataset or a pose file (docs/reconstruction.md)")->required();
  cmd->add_option("--poses", a->poses_file, "A pose file for the views (found in INPUT when INPUT is a folder)");
  cmd->add_option("--pose-format", a->pose_format, "auto, keyturn, stanford, tum or matrix")->capture_default_str();
  cmd->add_option("--views", a->views, "TUM only: the view files, one FILE or TIMESTAMP FILE a line");
  cmd->add_flag("--invert-poses", a->poses.invert, "The poses map the common frame into each view: invert them");
  cmd->add_option("--object", a->object, "CLASS/INSTANCE: the object to reconstruct from a dataset of several");
  cmd->add_option("--elevations", a->elevations, "Comma list of the dataset's elevations to use (default: all)");
  cmd->add_option("--model", a->model, "Pose model: auto (turntable for a calibrated dataset), free or turntable")
      ->capture_default_str();
  cmd->add_flag("--no-refine", a->no_refine, "Keep the poses as given (fuse and mesh only)");
  cmd->add_flag("--no-filter", a->no_filter, "Use the views as they are (no support-plane or background removal)");
  cmd->add_flag("--free-tilt", a->free_tilt,
                "Turntable: refine each camera's tilt from the object alone, not from the support plane (a support "
                "not square to the axis)");
  auto& r = a->options.registration;
  cmd->add_option("--voxel", r.voxel_m, "Registration resolution in metres (0: 1/250 of the object's size)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--min-overlap", r.min_overlap, "Fraction of a view a pair must share to be registered")
      ->capture_default_str()->check(CLI::Range(0.01, 1.0));
  cmd->add_option("--surface", a->surface,
                  "auto (TSDF when every view is an organized depth frame, else Poisson), poisson or tsdf")
      ->capture_default_str();
  cmd->add_option("--tsdf-voxel", a->options.tsdf.voxel_m, "TSDF voxel in metres (0: half the truncation, at most the fused cloud's)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--tsdf-truncation", a->options.tsdf.truncation_m,
                  "TSDF truncation in metres (0: 1.5 σ of the noise on the support plane)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--poisson-depth", a->options.poisson.depth, "Poisson octree depth")->capture_default_str()->check(CLI::Range(5, 12));
  cmd->add_option("--reference-poses", a->reference_poses, "True poses (keyturn pose list or .conf, one per view, same order): pose errors in the report");
  cmd->add_option("--reference-mesh", a->reference_mesh, "A true surface: fused-cloud distance and the mesh's F-score in the report");
  cmd->add_option("--perturb", a->perturb, "DEGREES,MILLIMETRES: move every pose but the first by this much first (tests)");
  cmd->add_option("--misset-axis", a->misset_axis,
                  "DEGREES,MILLIMETRES: mis-set each rig camera's axis calibration by this much first (a tilt and a "
                  "horizontal shift; tests)");
  cmd->add_option("--seed", a->seed, "Seed of --perturb and --misset-axis")->capture_default_str();
  cmd->add_flag("--quiet,-q", a->quiet, "No progress lines");
  cmd->add_option("--out,-o", a->out, "Output folder: cloud.ply, mesh.ply, poses.txt, report.json")->required();
  return {cmd, [a] { return runReconstruct(*a); }};
}

}  // namespace keyturn::app
