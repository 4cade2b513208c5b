#include "keyturn/rig/object_enrollment.h"

#include <chrono>
#include <cmath>
#include <filesystem>

#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset_layout.h"
#include "keyturn/dataset/dataset_views.h"
#include "keyturn/dataset/view_poses.h"
#include "keyturn/learning/model_predictions.h"

namespace keyturn::rig {
namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::string enrollmentMesh(const std::string& input) {
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

EnrolledObject enrollObject(ObjectEnrollment request, const EnrollmentProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  ObjectSimulation& sim = request.simulation;
  EnrolledObject result;
  result.before = learning::loadModel(request.model);
  const learning::Model& model = result.before;
  result.label = learning::enrolledClass(model, sim.object.cls, sim.object.instance, request.model);
  sim.checkMesh();
  if (sim.dir.empty()) sim.dir = request.out + ".views";
  // The rendered views go with the enrollment, also when it fails or is cancelled half-way (a
  // progress callback that throws): kept only when asked for (they then resume).
  struct RemoveViews {
    const ObjectEnrollment& request;
    ~RemoveViews() {
      std::error_code ec;
      if (!request.keep_views) fs::remove_all(request.simulation.dir, ec);
    }
  } remove_views{request};

  progress.rendering(sim.views(), result.label, sim.dir);
  simulateObject(sim, progress.view_rendered);
  progress.rendered();
  result.render_s = secondsSince(t0);

  const auto t1 = std::chrono::steady_clock::now();
  learning::FeatureTable views = learning::modelLayout(model, request.model);
  std::vector<double> azimuths;
  for (SimulatedCamera c : sim.cameras) {
    const std::string dataset = sim.datasetOf(c);
    std::vector<std::string> bad;
    const auto labelled = dataset::datasetViews(dataset, &bad);
    if (progress.describe)
      for (const auto& b : bad) progress.describe->warning(dataset::manifestPath(dataset) + ": skipped " + b);
    const learning::FeatureTable t = learning::describeForModel(model, labelled, request.jobs, progress.describe, request.model);
    const auto poses = dataset::datasetAzimuths(dataset);
    for (const auto& row : t.rows) {
      const auto it = poses.find(row.id);
      azimuths.push_back(it == poses.end() ? std::nan("") : it->second);
    }
    learning::appendRows(views, t, dataset);
  }
  result.describe_s = secondsSince(t1);

  const auto t2 = std::chrono::steady_clock::now();
  progress.retraining(model, views.rows.size());
  result.enrollment = learning::enrollObject(model, views, azimuths, request.model);
  learning::saveModel(request.out, result.enrollment.model);
  result.train_s = secondsSince(t2);
  return result;
}

}  // namespace keyturn::rig
