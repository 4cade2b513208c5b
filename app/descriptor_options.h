#pragma once
// Command-line options that shape a view descriptor, shared by describe and bench.
#include <CLI/CLI.hpp>
#include <string>

#include "keyturn/core/descriptor.h"
#include "keyturn/learning/feature_spec.h"

namespace keyturn::app {

struct DescriptorFlags {
  std::string features = "kpd2,kpd3,kpa3,gkpd1,gkpd2,gkpcd2";
  int bins = 32;
  std::string range = "fixed";
  double extent = 0.35;
  bool no_filter = false;
  bool no_plane = false;
  double max_range = 3.0;
  double jump_edge_angle = 10.0;
  double iss_frame = 6.0, iss_nms = 4.0, iss_density = 2.0;
  double graph_radius = 3.5;
  double samples_across = learning::FeatureParams().samples_across;
  int max_keypoints = learning::FeatureParams().max_keypoints;
  int osada_samples = 20000;
  unsigned long long seed = 7;
  int low_keypoints = 10;

  // with_features = false: the dataset tools, whose feature cache holds every block.
  void add(CLI::App& cmd, bool with_features = true);
  DescriptorOptions toOptions() const;  // throws keyturn::Error on bad values
  learning::FeatureParams params() const;
};

}  // namespace keyturn::app
