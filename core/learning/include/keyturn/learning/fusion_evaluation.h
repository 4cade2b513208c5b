#pragma once
// keyturn evaluate's fusion protocol (docs/results.md, "Multi-view fusion"): for each fold of a
// group-wise protocol (leave-instance, leave-elevation), the classifier and the pose references
// are fitted on the training views; each held-out capture group (instance at one elevation) is
// then read as sequences of views at set azimuth offsets, starting from every one of its views,
// and each fusion method's answer after n views is judged — beside the same sequences with their
// poses shuffled among their views (the control: a method that uses the poses should lose).
#include <cstdint>
#include <string>
#include <vector>

#include "keyturn/core/report_plot_specs.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/protocols.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning {

// How a sequence's views are spread: n views evenly over `spread_deg` (n = 1: one view), or
// n views `step_deg` apart.
struct FusionSchedule {
  std::string name;        // "over 90°", "step 30°"
  double spread_deg = 0;   // > 0: spread; else step
  double step_deg = 0;
  std::vector<double> offsets(int views) const;
};
// "90" → over 90°; "step30" → 30° apart. Throws keyturn::Error naming a malformed schedule.
FusionSchedule parseFusionSchedule(const std::string& text);

struct FusionEvaluationOptions {
  FusionOptions fusion;                       // method ignored: every method in `methods` is measured
  std::vector<std::string> methods = fusionMethods();
  std::vector<FusionSchedule> schedules;      // the first one also measures the stopping rule
  int max_views = 6;
  double tolerance_deg = 2.5;                 // a wanted azimuth matches a view this close
  std::uint64_t seed = 7;                     // the poses' shuffles
};

// Pooled over the folds of one protocol: per schedule, method and pose order, for n = 1 … max_views.
struct FusionCurve {
  std::string schedule, method;
  bool shuffled = false;
  std::vector<std::size_t> sequences, correct;  // [n - 1]
  std::vector<double> true_belief;              // summed belief in the true class after n views
  double accuracy(std::size_t n) const;         // n from 1; NaN without sequences
  double meanTrueBelief(std::size_t n) const;
};

// The stopping rule on the first schedule: views taken up to max_views until the belief is certain.
struct FusionStopping {
  std::string method;
  std::size_t sequences = 0, correct = 0, views = 0;  // views: summed over sequences
};

struct FusionProtocolResult {
  std::string protocol, label_kind;
  std::size_t folds = 0, test_views = 0, single_view_correct = 0;  // every test view alone
  std::vector<FusionCurve> curves;
  std::vector<FusionStopping> stopping;
};

// The table's rows' azimuths (degrees, one per row; NaN for a row without a pose, which is then
// left out of sequences). `protocol` must be leave-instance or leave-elevation (makeProtocol).
// Throws keyturn::Error for another protocol, a size mismatch, or a protocol without folds.
FusionProtocolResult evaluateFusion(const FeatureTable& table, const std::vector<double>& azimuth_deg,
                                    const std::vector<std::string>& blocks, const std::string& protocol,
                                    const ClassifierParams& params, const FusionEvaluationOptions& options,
                                    int jobs = 0);

struct FusionReport {
  std::string json, markdown, csv;
  ReportPlots plots;
};
// dataset and features name the run in the report.
FusionReport fusionReport(const std::vector<FusionProtocolResult>& results, const std::string& dataset,
                          const std::string& features, const std::string& classifier,
                          const FusionEvaluationOptions& options);

}  // namespace keyturn::learning
