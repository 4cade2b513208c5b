#pragma once
// Multi-view fusion's command-line options (learning/view_fusion.h), shared by
// `keyturn classify --fuse` and `keyturn evaluate --protocol fusion`, and the
// latter's run (app/fusion_evaluate.cpp).
#include <CLI/CLI.hpp>
#include <string>

#include "keyturn/core/depth_image.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/learning/classifier.h"
#include "keyturn/learning/fusion_evaluation.h"

namespace keyturn::app {

struct FusionFlags {
  learning::FusionOptions fusion;
  int views = 6;                                  // evaluate: sequences of 1 … views
  std::string schedules = "90,step30,step90";     // evaluate: how a sequence's views are spread
  // evaluate: the flags' values as the library's options (schedules parsed, each checked).
  learning::FusionEvaluationOptions evaluationOptions() const;
  void addStopBelief(CLI::App& cmd);
  void addEvaluationOptions(CLI::App& cmd);
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

// keyturn classify --fuse: one object's views fused in order (app/classify_fusion.cpp).
struct ClassifyFusionArgs {
  std::string model;
  std::vector<std::string> inputs;  // view files, or one dataset folder with `object`
  std::string object;               // CLASS/INSTANCE[/ELEVATION] of a dataset
  std::string azimuths;             // a dataset's views at these angles only ("0,45,90")
  bool json = false, quiet = false;
  int jobs = 0;
  FusionFlags flags;
};
int runClassifyFused(const ClassifyFusionArgs& a, const DepthImageOptions& depth);

}  // namespace keyturn::app
