#pragma once
// Multi-view fusion's command-line options (learning/view_fusion.h), shared by
// `keyturn classify --fuse`, `keyturn evaluate --protocol fusion` and `--protocol nbv`
// (next best view), and the latter two's runs (app/fusion_evaluate.cpp, app/nbv_evaluate.cpp).
#include <CLI/CLI.hpp>
#include <string>

#include "keyturn/core/depth_image.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/learning/classifier.h"
#include "keyturn/learning/fusion_evaluation.h"
#include "keyturn/learning/nbv_evaluation.h"

namespace keyturn::app {

struct FusionFlags {
  learning::FusionOptions fusion;
  int views = 6;                                  // evaluate: sequences of 1 … views
  std::string schedules = "90,step30,step90";     // evaluate: how a sequence's views are spread
  double nbv_step = 45;                           // evaluate nbv: the turns next best view may choose
  int nbv_start_every = 1;                        // evaluate nbv: sequences from every k-th view
  double nbv_window = 45;                         // evaluate nbv: the per-angle confusions' window
  // evaluate: the flags' values as the library's options (schedules parsed, each checked).
  learning::FusionEvaluationOptions evaluationOptions() const;
  // evaluate nbv: the fixed steps are --fusion-schedule's when given, else step45 (3 views over 90°).
  learning::NbvEvaluationOptions nbvOptions() const;
  void addStopBelief(CLI::App& cmd);
  void addEvaluationOptions(CLI::App& cmd);

 private:
  CLI::Option* schedule_option_ = nullptr;  // to tell a given --fusion-schedule from its default
};

struct FusionEvaluateArgs {
  std::string dataset, features, classifier, out;
  learning::ClassifierParams params;
  DescriptorOptions options;
  int jobs = 0;
  bool json = false, quiet = false;
  FusionFlags flags;
};

// keyturn evaluate --protocol fusion: leave-instance and leave-elevation where the dataset has them.
int runFusionEvaluate(const FusionEvaluateArgs& a);
// keyturn evaluate --protocol nbv: next best view against fixed steps, the same protocols.
int runNbvEvaluate(const FusionEvaluateArgs& a);

// What both runs share: one feature set and one classifier (else one line naming the flag), and
// the dataset's features with each row's turntable angle and the group-wise protocols it has.
void checkOneFeatureSetAndClassifier(const FusionEvaluateArgs& a, const std::string& protocol);
struct PosedTable {
  learning::FeatureTable table;
  std::vector<double> azimuths;          // one per row; NaN without a pose
  std::vector<std::string> protocols;    // leave-instance, leave-elevation where the dataset has them
};
PosedTable posedTable(const FusionEvaluateArgs& a, const std::string& protocol);

// keyturn classify --fuse: one object's views fused in order (app/classify_fusion.cpp).
struct ClassifyFusionArgs {
  std::string model;
  std::vector<std::string> inputs;  // view files, or one dataset folder with `object`
  std::string object;               // CLASS/INSTANCE[/ELEVATION] of a dataset
  std::string azimuths;             // a dataset's views at these angles only ("0,45,90")
  bool turns = false;               // every turn of one dataset folder, each fused alone
  bool json = false, quiet = false;
  int jobs = 0;
  FusionFlags flags;
};
int runClassifyFused(const ClassifyFusionArgs& a, const DepthImageOptions& depth);

}  // namespace keyturn::app
