#pragma once
// keyturn evaluate's run and report (docs/results.md, the paper's Table 2):
// accuracy (mean ± spread over folds) per bin count, feature set, classifier and
// protocol on one dataset's views, written as CSV, JSON and Markdown, with the
// plots the Markdown links to (confusion matrices of the best rows, per-class
// PDFs, the bin sweep), and for the open-set protocol its figures and ROC curves.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"
#include "keyturn/learning/evaluation.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/open_set_calibration.h"
#include "keyturn/learning/protocols.h"
#include "keyturn/core/report_plot_specs.h"

namespace keyturn::learning {

struct EvaluationPlan {
  std::string dataset;                      // named in the report
  std::vector<std::string> feature_sets;    // "kpd2+gkpd2" …
  std::vector<std::string> classifiers, protocols;
  std::vector<int> bins;
  std::uint64_t split_seed = 7;
  ClassifierParams params;                  // kind is each row's classifier
  int jobs = 0;
  int low_keypoints = 0;                    // "views with K < low_keypoints" in the summary
  std::optional<LabelKind> label;           // none: each protocol's own (makeProtocol)
  int inner_folds = 3;                      // per fold, for a feature set 'A|B' (evaluateFoldChoosing)
  std::vector<std::string> train_extra;     // datasets of twins to train on (training_twins.h)
  // The open-set protocol's methods (all, measured side by side), stated false-accept rate and groups.
  OpenSetOptions open_set = {openSetMethods()};
  // Each view's turntable angle by view id (dataset/view_poses.h): the open-set protocol then also
  // reads its folds' views as turning sequences fused by pose. Empty: single views only.
  std::map<std::string, double> azimuth_deg;
};

struct EvaluationRow {
  int bins = 0;
  std::string protocol, features, classifier;
  const Protocol* proto = nullptr;
  Evaluation ev;
};

struct EvaluationRun {
  EvaluationPlan plan;
  std::map<int, FeatureTable> tables;       // per bin count
  std::map<int, double> describe_s;         // time to describe (or load) each table, twins included
  std::map<int, TwinRows> twins;            // per bin count: the rows appended from plan.train_extra
  std::vector<std::unique_ptr<Protocol>> protocols;
  std::vector<EvaluationRow> rows;
  double total_s = 0;                       // from prepareEvaluation to the end of evaluateRows
  std::size_t totalFolds() const;
};

// One training of the run: a row's fold. The run's trainings are numbered in row and fold
// order; shard s of n (s from 0) takes those numbered j ≡ s (mod n), so every shard gets a
// mix of the rows (of every classifier) and the shards' costs stay close.
struct FoldJob {
  std::size_t row = 0, fold = 0;
};
// Throws keyturn::Error for a shard outside 0 .. shards - 1.
std::vector<FoldJob> foldJobs(const EvaluationRun& run, int shard = 0, int shards = 1);

// Checks the plan (at least one of each, classifier and block names), gets each bin count's
// table from describe(bins), appends the twins of plan.train_extra from describe_extra(dataset,
// bins) (the folds are the protocols' on the dataset's own views) and lays out the rows. Throws
// keyturn::Error naming what is wrong.
EvaluationRun prepareEvaluation(
    const EvaluationPlan& plan, const std::function<FeatureTable(int bins)>& describe,
    const std::function<FeatureTable(const std::string& dataset, int bins)>& describe_extra = {});
// Trains and tests the shard's folds (all of them by default) on plan.jobs threads; fold_done after each.
void evaluateRows(EvaluationRun& run, const std::function<void()>& fold_done = nullptr, int shard = 0,
                  int shards = 1);

struct EvaluationReport {
  std::string csv, json, markdown;  // report.csv, report.json, report.md
  ReportPlots plots;                // confusion/*.png, pdfs/*.png, bins_*.png
};
EvaluationReport evaluationReport(const EvaluationRun& run);

}  // namespace keyturn::learning
