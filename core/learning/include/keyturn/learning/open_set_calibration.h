#pragma once
// Calibrating the open-set threshold on the training data's own folds: the training views'
// categories are shuffled into groups; each group in turn is left out of a training of the
// classifier (on the remaining views, their classes renumbered) and its views scored as
// unknowns. The threshold accepts the stated fraction of those unknown scores; the scorer
// itself (knn's references) is then fitted on all the training views.
#include <cstdint>
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"
#include "keyturn/learning/open_set.h"

namespace keyturn::learning {

// The method `auto` picks: the best of the three on the open-set protocol's folds (docs/results.md,
// "Open-set answers"). Models are closed-set unless train is asked for open-set answers.
inline const char* defaultOpenSetMethod() { return "knn-relative"; }

struct OpenSetOptions {
  std::vector<std::string> methods = {defaultOpenSetMethod()};  // each calibrated on the same trainings
  double false_accept = 0.05;                  // the stated rate on unknown views
  int groups = 5;                              // at most; one training without each group
  // pooled: the stated rate on all the left-out views together; per-group: on each group's alone, so
  // that no left-out group is accepted more often (stricter; docs/results.md, "Why a fold's false
  // accepts stray from the stated rate" measures both). The turn threshold follows the same rule.
  std::string rule = "pooled";
  int neighbours = 1;                          // knn, knn-relative
  // knn-relative: the distance over the class's pooled scale, or also over the view's camera's factor
  // (open_set.h; docs/results.md, "Beyond the training conditions"). Rows without a camera: pooled.
  std::string scale_by = "camera";
  // knn-relative: each class's scale drawn toward the median class's, s_c^p · median^(1-p) (open_set.h;
  // 1: its own scale). docs/results.md, "Beyond the training conditions", measures p.
  double class_scale_power = 1;
  // knn-relative: a class's scale from its views' spread, or its instances' (open_set.h's class_spread;
  // docs/results.md, "A category model's unseen instances").
  std::string class_spread = "views";
  // knn, knn-relative: the distance measured (open_set.h): rms or l1. Fitting and the calibration alike.
  std::string distance = "rms";
  std::uint64_t seed = 7;                      // the categories' shuffle
  // false: data of fewer than three categories (nothing to leave out) gives a closed-set model
  // instead of an error (trainModel).
  bool required = true;
};

// train's choice by name: auto (the default method where the data has enough categories, else
// closed-set: required false), none (closed-set), max-probability, knn or knn-relative. Throws keyturn::Error
// for another name.
void setOpenSetMethod(OpenSetOptions& options, const std::string& method);

// Distinct categories needed to calibrate: one group left out, two classes still to train on.
constexpr std::size_t kOpenSetMinCategories = 3;

// Each training row's capture group (instance and elevation) and turntable angle (NaN: none), for
// the turn threshold: the left-out views read as turns of the table (turn_fusion.h).
struct TurnRows {
  std::vector<std::string> group;
  std::vector<double> azimuth_deg;
};

// One calibrated OpenSet per options.methods, in order. x, y: the training rows and their class
// indices (0 .. classes - 1, every class present); categories: each row's category (the unit left out).
// With turns (one per row), the turn threshold too, for the same rate on the left-out views' turns
// (left NaN when they form none). Throws keyturn::Error when fewer than three categories leave no
// group out with two classes to train on, or turns are not one per row. cameras (one per row, "" for
// none): each row's camera, for options.scale_by "camera"; the left-out views are scored with theirs.
// instances (one per row): each row's instance, needed for options.class_spread "instances".
std::vector<OpenSet> calibrateOpenSets(const Matrix& x, const std::vector<int>& y,
                                       const std::vector<std::string>& categories, const ClassifierParams& params,
                                       const OpenSetOptions& options, const TurnRows* turns = nullptr,
                                       const std::vector<std::string>* cameras = nullptr,
                                       const std::vector<std::string>* instances = nullptr);

// Class indices made contiguous over the classes present: y's values mapped to 0 .. n - 1 in
// increasing order; `present` (optional) receives the original index of each new one.
std::vector<int> compactClasses(const std::vector<int>& y, std::vector<int>* present = nullptr);

}  // namespace keyturn::learning
