#pragma once
// One fold of a multi-view protocol as fusion sees it, shared by evaluate's fusion and
// next-best-view protocols: the classifier trained on the fold's training views that have a
// turntable angle, with their pose references, and each test view's class probabilities,
// angle and pose evidence, grouped by capture group (instance and elevation).
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "keyturn/learning/classifier.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/protocols.h"
#include "keyturn/learning/view_fusion.h"

namespace keyturn::learning::detail {

std::string captureGroupOf(const FeatureRow& row);

struct TrainedFold {
  std::vector<std::size_t> train;  // the fold's training rows with a finite angle
  std::vector<int> y;
  std::vector<double> azimuth_deg;
  Matrix x;
  std::unique_ptr<Classifier> classifier;
  PoseReferences references;
};

TrainedFold trainFold(const FeatureTable& t, const std::vector<double>& az, const std::vector<std::string>& blocks,
                      const Labels& labels, const Fold& fold, const ClassifierParams& params, double bin_deg);

struct FoldViews {
  std::vector<FusionView> views;  // per test view
  std::vector<int> truth;
  std::vector<std::string> group;
  std::size_t single_correct = 0;
};

FoldViews predictTestViews(const TrainedFold& trained, const FeatureTable& t, const std::vector<double>& az,
                           const std::vector<std::string>& blocks, const Labels& labels, const Fold& fold);

// Each capture group's views that have an angle: (angle, index into views), by group name.
using GroupedViews = std::map<std::string, std::vector<std::pair<double, int>>>;
GroupedViews groupsByAngle(const std::vector<FusionView>& views, const std::vector<std::string>& group);

// The view of a group (its views' angles and indices) nearest azimuth a within the tolerance; -1 when none.
int viewAt(const std::vector<std::pair<double, int>>& members, double a, double tolerance);

// The views of a group at start_deg + each offset (viewAt's indices), in the offsets' order; it stops
// at the first offset with no view, so it is shorter than offsets when the group lacks one.
std::vector<int> viewsAtOffsets(const std::vector<std::pair<double, int>>& members, double start_deg,
                                const std::vector<double>& offsets, double tolerance);

}  // namespace keyturn::learning::detail
