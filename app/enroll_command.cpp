// keyturn enroll: a new object added to a trained model from its mesh (a mesh file, or the folder
// keyturn reconstruct writes, holding mesh.ply). The work is rig::enrollObject's
// (rig/object_enrollment.h, which the studio's Enroll… calls too); this parses, calls and prints.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.h"
#include "cached_features.h"
#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"
#include "keyturn/rig/object_enrollment.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct EnrollArgs {
  std::string mesh, cls, instance, model, out, views;
  std::string elevations = "30,45,60", cameras = "sr4000,openni2";
  double step = 5;
  unsigned long long seed = 1;
  int jobs = 0;
  bool quiet = false;
};

int runEnroll(const EnrollArgs& a) {
  rig::ObjectEnrollment request;
  rig::ObjectSimulation& sim = request.simulation;
  sim.object = {a.cls, a.instance, rig::enrollmentMesh(a.mesh)};
  sim.cameras = rig::parseSimulatedCameras(a.cameras);
  sim.elevations = parseNumberList(a.elevations, "--elevations");
  sim.step_deg = a.step;
  sim.seed = a.seed;
  sim.dir = a.views;
  request.keep_views = !a.views.empty();
  request.model = a.model;
  request.out = a.out;
  request.jobs = a.jobs;

  std::unique_ptr<Progress> render;
  DescribeProgressLine describe(a.quiet);
  rig::EnrollmentProgress progress;
  progress.rendering = [&](std::size_t views, const std::string& label, const std::string& dir) {
    render = std::make_unique<Progress>("render", views, !a.quiet);
    if (!a.quiet)
      std::cerr << "keyturn enroll: rendering " << views << " views of " << label << " (" << a.cameras << "; "
                << a.elevations << "°, every " << a.step << "°) → " << dir << "\n";
  };
  progress.view_rendered = [&] { render->advance(); };
  progress.rendered = [&] { render->finish(); };
  progress.describe = &describe;
  progress.retraining = [&](const learning::Model& model, std::size_t new_views) {
    if (!a.quiet)
      std::cerr << "keyturn enroll: retraining on the model's " << model.info.training_views.views.size() << " views and "
                << new_views << " new ones (" << model.info.params.kind << ", open set " << model.info.open_set.method
                << " re-calibrated for " << 100 * model.info.open_set.false_accept << " % false accepts)\n";
  };
  const rig::EnrolledObject r = rig::enrollObject(request, progress);
  if (!a.quiet) {
    const learning::Enrollment& e = r.enrollment;
    const learning::OpenSet& before = r.before.info.open_set;
    const learning::OpenSet& os = e.model.info.open_set;
    std::cerr << std::fixed << std::setprecision(4) << "keyturn enroll: " << r.label << " added: "
              << e.model.info.classes.size() << " classes, " << e.new_views << " new views";
    if (e.skipped) std::cerr << " (" << e.skipped << " not described, left out)";
    std::cerr << "; threshold " << before.threshold << " → " << os.threshold;
    if (std::isfinite(os.turn_threshold)) std::cerr << ", a turn's " << before.turn_threshold << " → " << os.turn_threshold;
    std::cerr << std::setprecision(1) << "; render " << formatDuration(r.render_s) << ", describe "
              << formatDuration(r.describe_s) << ", retrain " << formatDuration(r.train_s) << " → " << a.out << "\n";
  }
  return 0;
}

}  // namespace

Command addEnrollCommand(CLI::App& app) {
  auto a = std::make_shared<EnrollArgs>();
  auto* cmd = app.add_subcommand(
      "enroll", "Add a new object to a model from its mesh: training views rendered through the simulated cameras, "
                "the model retrained and its open set re-calibrated");
  cmd->add_option("mesh", a->mesh, "The object's mesh (.ply, .obj, .stl, .off; metres, z up, base on z = 0), or a "
                                   "keyturn reconstruct folder (its mesh.ply)")
      ->required();
  cmd->add_option("--class", a->cls, "The object's category")->required();
  cmd->add_option("--instance", a->instance, "The object's instance name (its class in an instance-labelled model)")
      ->required();
  cmd->add_option("--model", a->model, "The model to add it to (keyturn train with an open set knn or knn-relative)")
      ->required();
  cmd->add_option("--out,-o", a->out, "The new model's folder (may be --model's)")->required();
  cmd->add_option("--cameras", a->cameras, "Simulated cameras rendering the training views, comma-separated")
      ->capture_default_str();
  cmd->add_option("--elevations", a->elevations, "Camera elevations (°), comma-separated")->capture_default_str();
  cmd->add_option("--step", a->step, "Turntable step (°) between training views")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Sensor noise seed of the rendered views")->capture_default_str();
  cmd->add_option("--views", a->views, "Keep the rendered views: one dataset per camera in this folder (resumed "
                                       "when run again); else they go once the model is written");
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views when describing");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  return {cmd, [a] { return runEnroll(*a); }};
}

}  // namespace keyturn::app
