#pragma once
// keyturn bench --scaling: the whole chain timed against input size, with PCL's
// ISSKeypoint3D and ESF on the same clouds in the same run, as JSON and a table.
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "keyturn/bench/view_timing.h"
#include "keyturn/core/depth_image.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/core/report_plot_specs.h"

namespace keyturn::bench {

struct ScalingArgs {
  std::string file;                 // an organized frame (or an already segmented object)
  DepthImageOptions depth;          // when the file is a depth image
  std::vector<std::size_t> sizes;   // input points per row
  BenchRuns runs;
  unsigned long long seed = 7;      // for the object subsets
  std::function<void(const std::string&)> warn;  // a row left out or failed, a cut that failed; may be empty
};

// The sizes the issue asks for: 1k … 307,200 = a full 640 × 480 frame.
std::vector<std::size_t> defaultScalingSizes();

// Keys: source, width, height, organized, valid_points, object_points, seed, repetitions,
// pcl_repetitions, threads, failed and rows (benchView's keys plus size, kind, input; or error).
// Every row is timed even when one fails. Throws keyturn::Error when no size fits the input.
nlohmann::json runScaling(const ScalingArgs& args, const DescriptorOptions& options);

// The table `keyturn bench --scaling` prints; its first line begins with the source's name (the
// CLI puts its command before it).
std::string scalingTable(const nlohmann::json& scaling);
// Its log-log plot of time against size, to be drawn into file (ui/plots/report_plots.h).
CurvePlot scalingPlot(const nlohmann::json& scaling, const std::string& file);

}  // namespace keyturn::bench
