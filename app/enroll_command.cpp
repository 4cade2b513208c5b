// keyturn enroll: a new object added to a trained model from its mesh (a mesh file, or the folder
// keyturn reconstruct writes, holding mesh.ply): its training views rendered through the simulated
// cameras by the built-in model's recipe (rig/object_simulation.h), described with the model's
// parameters, and the model retrained with them (learning/model_enrollment.h).
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "dataset_features.h"
#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"
#include "keyturn/dataset/view_poses.h"
#include "keyturn/learning/model_enrollment.h"
#include "keyturn/learning/model_predictions.h"
#include "keyturn/rig/object_simulation.h"
#include "progress.h"

namespace keyturn::app {
namespace {

namespace fs = std::filesystem;

struct EnrollArgs {
  std::string mesh, cls, instance, model, out, views;
  std::string elevations = "30,45,60", cameras = "sr4000,openni2";
  double step = 5;
  unsigned long long seed = 1;
  int jobs = 0;
  bool quiet = false;
};

// A mesh file, or a reconstruction folder's mesh.ply.
std::string meshOf(const std::string& input) {
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    const fs::path mesh = fs::path(input) / "mesh.ply";
    if (!fs::is_regular_file(mesh, ec))
      throw Error(input + ": a folder without mesh.ply (give a mesh file, or the folder keyturn reconstruct wrote)");
    return mesh.string();
  }
  if (!fs::exists(input, ec)) throw Error(input + ": no such mesh file or reconstruction folder");
  return input;
}

std::vector<rig::SimulatedCamera> camerasOf(const std::string& list) {
  std::vector<rig::SimulatedCamera> out;
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    out.push_back(rig::parseSimulatedCamera(list.substr(at, comma - at)));
    at = comma + 1;
  }
  return out;
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int runEnroll(const EnrollArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  rig::ObjectSimulation sim;
  sim.object = {a.cls, a.instance, meshOf(a.mesh)};
  sim.cameras = camerasOf(a.cameras);
  sim.elevations = parseNumberList(a.elevations, "--elevations");
  sim.step_deg = a.step;
  sim.seed = a.seed;
  // Everything that can refuse is checked before the minutes of rendering.
  const learning::Model model = learning::loadModel(a.model);
  const std::string label = learning::enrolledClass(model, a.cls, a.instance, a.model);
  sim.checkMesh();
  const bool keep = !a.views.empty();
  sim.dir = keep ? a.views : a.out + ".views";

  Progress render("render", sim.views(), !a.quiet);
  if (!a.quiet)
    std::cerr << "keyturn enroll: rendering " << sim.views() << " views of " << label << " (" << a.cameras << "; "
              << a.elevations << "°, every " << a.step << "°) → " << sim.dir << "\n";
  rig::simulateObject(sim, [&] { render.advance(); });
  render.finish();
  const double render_s = secondsSince(t0);

  const auto t1 = std::chrono::steady_clock::now();
  learning::FeatureTable views = learning::modelLayout(model, a.model);
  std::vector<double> azimuths;
  for (rig::SimulatedCamera c : sim.cameras) {
    const std::string dataset = sim.datasetOf(c);
    DescribeProgressLine progress(a.quiet);
    const learning::FeatureTable t = learning::describeForModel(model, datasetViews(dataset), a.jobs, &progress, a.model);
    const auto poses = dataset::datasetAzimuths(dataset);
    for (const auto& row : t.rows) {
      const auto it = poses.find(row.id);
      azimuths.push_back(it == poses.end() ? std::nan("") : it->second);
    }
    learning::appendRows(views, t, dataset);
  }
  const double describe_s = secondsSince(t1);

  const auto t2 = std::chrono::steady_clock::now();
  if (!a.quiet)
    std::cerr << "keyturn enroll: retraining on the model's " << model.info.training_views.views.size() << " views and "
              << views.rows.size() << " new ones (" << model.info.params.kind << ", open set " << model.info.open_set.method
              << " re-calibrated for " << 100 * model.info.open_set.false_accept << " % false accepts)\n";
  const learning::Enrollment e = learning::enrollObject(model, views, azimuths, a.model);
  learning::saveModel(a.out, e.model);
  const double train_s = secondsSince(t2);
  if (!keep) fs::remove_all(sim.dir);
  if (!a.quiet) {
    const learning::OpenSet& os = e.model.info.open_set;
    std::cerr << std::fixed << std::setprecision(4) << "keyturn enroll: " << label << " added: "
              << e.model.info.classes.size() << " classes, " << e.new_views << " new views";
    if (e.skipped) std::cerr << " (" << e.skipped << " not described, left out)";
    std::cerr << "; threshold " << model.info.open_set.threshold << " → " << os.threshold;
    if (std::isfinite(os.turn_threshold)) std::cerr << ", a turn's " << model.info.open_set.turn_threshold << " → " << os.turn_threshold;
    std::cerr << std::setprecision(1) << "; render " << formatDuration(render_s) << ", describe "
              << formatDuration(describe_s) << ", retrain " << formatDuration(train_s) << " → " << a.out << "\n";
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
