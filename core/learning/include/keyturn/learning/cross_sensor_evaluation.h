#pragma once
// Across sensors (keyturn evaluate --protocol cross-sensor): the same views seen through two cameras
// (a dataset and its twin through another camera, keyturn simulate --camera), a model trained on the
// first camera's views, on the second's, or on both, and each tested on both cameras' views of an
// elevation no training saw (one fold per elevation left out). A cell therefore measures what the
// camera changes, not views seen in training; the diagonal is the same camera at a new elevation.
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/core/report_plot_specs.h"
#include "keyturn/learning/classifier.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/protocols.h"

namespace keyturn::learning {

// What a model is trained on: the first camera's views, the second's, or both.
enum class CrossSensorTraining { First, Second, Both };

struct CrossSensorData {
  FeatureTable table;                   // the first camera's rows, then the second's (appendTwins)
  std::size_t first_rows = 0;           // rows [0, first_rows) are the first camera's
  std::array<std::string, 2> cameras;   // their names in the report (e.g. the datasets' folders)
};

// The two datasets' tables as one: second's rows are the same views as first's (their ids), through
// the other camera. Throws keyturn::Error naming second_name for other blocks or parameters, a view
// first lacks, or views of fewer than two elevations (nothing to leave out).
CrossSensorData crossSensorData(FeatureTable first, const FeatureTable& second, std::array<std::string, 2> cameras);

struct CrossSensorOptions {
  std::vector<std::string> feature_sets, classifiers;  // each pair measured on the same folds
  ClassifierParams params;                              // kind is each cell's classifier
  LabelKind label = LabelKind::Instance;
  int jobs = 0;
};

struct CrossSensorCell {
  std::string features, classifier;
  CrossSensorTraining trained = CrossSensorTraining::First;
  int tested = 0;                      // 0: the first camera's views, 1: the second's
  std::size_t views = 0, correct = 0;  // pooled over the folds
  std::vector<double> fold_accuracy;   // per elevation left out, in the elevations' order
  double accuracy() const { return views ? static_cast<double>(correct) / static_cast<double>(views) : 0.0; }
};

struct CrossSensorResult {
  std::vector<std::string> elevations;  // the folds: one elevation left out each
  std::string label_kind;
  std::vector<CrossSensorCell> cells;   // per feature set and classifier: 3 trainings × 2 cameras
};

// Trainings the run makes (feature sets × classifiers × 3 × elevations), for a progress bar.
std::size_t crossSensorTrainings(const CrossSensorData& data, const CrossSensorOptions& options);
// Trains and tests every fold on options.jobs threads; training_done after each training.
CrossSensorResult evaluateCrossSensor(const CrossSensorData& data, const CrossSensorOptions& options,
                                      const std::function<void()>& training_done = nullptr);

struct CrossSensorReport {
  std::string csv, json, markdown;
  ReportPlots plots;  // accuracy per (trained on → tested on), one series per feature set and classifier
};
CrossSensorReport crossSensorReport(const CrossSensorResult& result, const CrossSensorData& data,
                                    const std::array<std::string, 2>& datasets);

}  // namespace keyturn::learning
