// keyturn evaluate --protocol cross-sensor: the dataset and its twin through another camera
// (--other-camera), trained on either or both and tested on each, one elevation left out at a time
// (learning/cross_sensor_evaluation.h runs and reports it).
#include <filesystem>
#include <iostream>

#include "cross_sensor_evaluate.h"
#include "cached_features.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/cross_sensor_evaluation.h"
#include "learning_options.h"
#include "progress.h"
#include "report_files.h"

namespace keyturn::app {
namespace {

// A camera's name in the report: its dataset's folder name.
std::string cameraName(const std::string& dataset) {
  const std::filesystem::path p = std::filesystem::path(dataset).lexically_normal();
  const std::string name = (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
  return name.empty() ? dataset : name;
}

}  // namespace

int runCrossSensorEvaluate(const CrossSensorEvaluateArgs& a) {
  if (a.other_camera.empty())
    throw Error("--protocol cross-sensor needs --other-camera DATASET: the same views through another camera "
                "(keyturn simulate --camera openni2 with the same objects, elevations and step)");
  std::array<std::string, 2> cameras{cameraName(a.dataset), cameraName(a.other_camera)};
  if (cameras[0] == cameras[1]) cameras = {a.dataset, a.other_camera};
  learning::CrossSensorOptions o;
  o.feature_sets = splitList(a.features);
  o.classifiers = splitList(a.classifiers);
  if (o.feature_sets.empty() || o.classifiers.empty()) throw Error("--protocol cross-sensor: give --features and --classifier");
  o.params = a.params;
  o.label = a.label;
  o.jobs = a.jobs;
  const learning::CrossSensorData data = learning::crossSensorData(
      datasetFeatures(a.dataset, a.options, a.jobs, a.quiet, o.feature_sets),
      datasetFeatures(a.other_camera, a.options, a.jobs, a.quiet, o.feature_sets),
      cameras);
  Progress progress("evaluate", learning::crossSensorTrainings(data, o), !a.quiet);
  const learning::CrossSensorResult result = learning::evaluateCrossSensor(data, o, [&] { progress.advance(); });
  progress.finish();
  const learning::CrossSensorReport report = learning::crossSensorReport(result, data, {a.dataset, a.other_camera});
  writeReportFiles(a.out, report);
  if (a.json) std::cout << report.json;
  if (!a.quiet)
    std::cerr << "keyturn evaluate: cross-sensor → " << (std::filesystem::path(a.out) / "report.md").string() << "\n";
  return 0;
}

}  // namespace keyturn::app
