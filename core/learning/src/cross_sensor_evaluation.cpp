#include "keyturn/learning/cross_sensor_evaluation.h"

#include <algorithm>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>

#include "keyturn/core/error.h"
#include "keyturn/core/parallel_for.h"
#include "keyturn/learning/training_twins.h"
#include "report_numbers.h"

namespace keyturn::learning {
namespace {

using detail::percent;

constexpr std::array<CrossSensorTraining, 3> kTrainings = {CrossSensorTraining::First, CrossSensorTraining::Second,
                                                           CrossSensorTraining::Both};

bool trainsOn(CrossSensorTraining t, int camera) {
  return t == CrossSensorTraining::Both || (camera == 0) == (t == CrossSensorTraining::First);
}

std::vector<std::string> elevationsOf(const CrossSensorData& d) {
  std::set<std::string> e;
  for (std::size_t r = 0; r < d.first_rows; ++r) e.insert(d.table.rows[r].elevation);
  return {e.begin(), e.end()};
}

// One training: its feature set and classifier, what it trains on, the elevation it leaves out.
struct Job {
  std::size_t set = 0, classifier = 0, training = 0, elevation = 0;
  std::array<std::size_t, 2> views{}, correct{};  // per camera tested
};

void runJob(const CrossSensorData& d, const CrossSensorOptions& o, const Labels& labels, const std::string& left_out,
            Job& job) {
  std::vector<std::size_t> train, test;
  std::vector<int> y;
  for (std::size_t r = 0; r < d.table.rows.size(); ++r) {
    const int camera = r < d.first_rows ? 0 : 1;
    if (d.table.rows[r].elevation == left_out) {
      test.push_back(r);
    } else if (trainsOn(kTrainings[job.training], camera)) {
      train.push_back(r);
      y.push_back(labels.of_row[r]);
    }
  }
  const auto blocks = featureSetBlocks(o.feature_sets[job.set]);
  ClassifierParams params = o.params;
  params.kind = o.classifiers[job.classifier];
  auto clf = makeClassifier(params);
  clf->fit(d.table.select(blocks, train), y, static_cast<int>(labels.names.size()));
  const std::vector<int> predicted = argmaxRows(clf->predictProba(d.table.select(blocks, test)));
  for (std::size_t k = 0; k < test.size(); ++k) {
    const int camera = test[k] < d.first_rows ? 0 : 1;
    ++job.views[camera];
    job.correct[camera] += predicted[k] == labels.of_row[test[k]];
  }
}

std::string trainingName(CrossSensorTraining t, const std::array<std::string, 2>& cameras) {
  if (t == CrossSensorTraining::Both) return "both";
  return cameras[t == CrossSensorTraining::First ? 0 : 1];
}

}  // namespace

CrossSensorData crossSensorData(FeatureTable first, const FeatureTable& second, std::array<std::string, 2> cameras) {
  CrossSensorData d;
  d.first_rows = first.rows.size();
  d.cameras = std::move(cameras);
  appendTwins(first, second, d.cameras[1]);
  d.table = std::move(first);
  const auto elevations = elevationsOf(d);
  if (elevations.size() < 2)
    throw Error(d.cameras[0] + ": cross-sensor leaves one elevation out at a time, and its views have " +
                (elevations.empty() ? std::string("none") : "one (" + elevations.front() + ")"));
  return d;
}

std::size_t crossSensorTrainings(const CrossSensorData& d, const CrossSensorOptions& o) {
  return o.feature_sets.size() * o.classifiers.size() * kTrainings.size() * elevationsOf(d).size();
}

CrossSensorResult evaluateCrossSensor(const CrossSensorData& d, const CrossSensorOptions& o,
                                      const std::function<void()>& training_done) {
  CrossSensorResult res;
  res.elevations = elevationsOf(d);
  const Labels labels = labelRows(d.table, o.label);
  res.label_kind = labels.kindName();
  for (const auto& s : o.feature_sets) d.table.select(featureSetBlocks(s), {});  // a block the table lacks: now
  std::vector<Job> jobs;
  for (std::size_t s = 0; s < o.feature_sets.size(); ++s)
    for (std::size_t c = 0; c < o.classifiers.size(); ++c)
      for (std::size_t t = 0; t < kTrainings.size(); ++t)
        for (std::size_t e = 0; e < res.elevations.size(); ++e) jobs.push_back({s, c, t, e, {}, {}});
  std::mutex progress;
  parallelFor(jobs.size(), o.jobs, [&](std::size_t i) {
    runJob(d, o, labels, res.elevations[jobs[i].elevation], jobs[i]);
    if (training_done) {
      std::lock_guard<std::mutex> l(progress);
      training_done();
    }
  });
  for (std::size_t s = 0; s < o.feature_sets.size(); ++s)
    for (std::size_t c = 0; c < o.classifiers.size(); ++c)
      for (std::size_t t = 0; t < kTrainings.size(); ++t)
        for (int camera = 0; camera < 2; ++camera) {
          CrossSensorCell cell{o.feature_sets[s], o.classifiers[c], kTrainings[t], camera, 0, 0, {}};
          for (const Job& j : jobs)
            if (j.set == s && j.classifier == c && j.training == t) {
              cell.views += j.views[camera];
              cell.correct += j.correct[camera];
              cell.fold_accuracy.push_back(j.views[camera] ? static_cast<double>(j.correct[camera]) / j.views[camera] : 0.0);
            }
          res.cells.push_back(cell);
        }
  return res;
}

CrossSensorReport crossSensorReport(const CrossSensorResult& r, const CrossSensorData& d,
                                    const std::array<std::string, 2>& datasets) {
  CrossSensorReport rep;
  const auto& cams = d.cameras;
  nlohmann::json j = {{"protocol", "cross-sensor"},
                      {"datasets", {datasets[0], datasets[1]}},
                      {"cameras", {cams[0], cams[1]}},
                      {"label", r.label_kind},
                      {"elevations_left_out", r.elevations},
                      {"cells", nlohmann::json::array()}};
  std::string md = "# Across sensors: " + cams[0] + " and " + cams[1] + "\n\n" + "The same views through two cameras (`" +
                   datasets[0] + "`, `" + datasets[1] + "`). Each model is trained on one camera's views, the other's, or " +
                   "both, leaving one elevation out (folds: " + std::to_string(r.elevations.size()) +
                   "), and tested on both cameras' views of that elevation; top-1 accuracy (%), " + r.label_kind +
                   " labels, pooled over the folds. Gap: the trained camera's column minus the other's (for both: " +
                   "the larger minus the smaller).\n\n";
  md += "| features | classifier | trained on | tested on " + cams[0] + " | tested on " + cams[1] + " | gap |\n";
  md += "|---|---|---|---:|---:|---:|\n";
  rep.csv = "features,classifier,trained_on,tested_on,views,correct,accuracy\n";
  CurvePlot plot;
  plot.file = "cross_sensor.png";
  plot.title = "Top-1 accuracy across sensors (" + r.label_kind + ", elevation left out)";
  // The cameras numbered on the axis and named in its title: whole names under each point are elided.
  plot.x_label = "trained on → tested on (1: " + cams[0] + ", 2: " + cams[1] + ")";
  plot.y_label = "accuracy (%)";
  for (const char* trained : {"1", "2", "both"})
    for (const char* tested : {"1", "2"}) plot.x_categories.push_back(std::string(trained) + " → " + tested);
  for (std::size_t i = 0; i + 1 < r.cells.size(); i += 2) {
    const CrossSensorCell& a = r.cells[i];      // tested on the first camera
    const CrossSensorCell& b = r.cells[i + 1];  // … on the second
    const double gap = a.trained == CrossSensorTraining::First    ? a.accuracy() - b.accuracy()
                       : a.trained == CrossSensorTraining::Second ? b.accuracy() - a.accuracy()
                                                                   : std::abs(a.accuracy() - b.accuracy());
    md += "| " + a.features + " | " + a.classifier + " | " + trainingName(a.trained, cams) + " | " + percent(a.accuracy()) +
          " | " + percent(b.accuracy()) + " | " + percent(gap) + " |\n";
    for (const CrossSensorCell* c : {&a, &b}) {
      rep.csv += c->features + "," + c->classifier + "," + trainingName(c->trained, cams) + "," + cams[c->tested] + "," +
                 std::to_string(c->views) + "," + std::to_string(c->correct) + "," + percent(c->accuracy()) + "\n";
      j["cells"].push_back({{"features", c->features},
                            {"classifier", c->classifier},
                            {"trained_on", trainingName(c->trained, cams)},
                            {"tested_on", cams[c->tested]},
                            {"views", c->views},
                            {"correct", c->correct},
                            {"accuracy", c->accuracy()},
                            {"fold_accuracy", c->fold_accuracy}});
    }
    if (a.trained == CrossSensorTraining::First) plot.series.push_back({a.features + ", " + a.classifier, {}, {}});
    CurveSeries& s = plot.series.back();
    for (const CrossSensorCell* c : {&a, &b}) {
      s.x.push_back(static_cast<double>(s.x.size()));
      s.y.push_back(100 * c->accuracy());
    }
  }
  plot.y_min = 0;
  plot.y_max = 100;
  rep.plots.curves.push_back(plot);
  md += "\n![accuracy across sensors](cross_sensor.png)\n";
  rep.markdown = md;
  rep.json = j.dump(2) + "\n";
  return rep;
}

}  // namespace keyturn::learning
