#pragma once
// keyturn bench --scaling: the whole chain timed against input size, with PCL's
// ISSKeypoint3D and ESF on the same clouds in the same run, as a table, JSON and
// a log-log PNG.
#include <cstddef>
#include <string>
#include <vector>

#include "bench_view.h"
#include "keyturn/core/descriptor.h"

namespace keyturn::app {

struct ScalingArgs {
  std::string file;                 // an organized frame (or an already segmented object)
  std::vector<std::size_t> sizes;   // input points per row
  BenchRuns runs;
  bool json = false;
  std::string plot;                 // PNG path, or empty
  unsigned long long seed = 7;      // for the object subsets
};

// The sizes the issue asks for: 1k … 307,200 = a full 640 × 480 frame.
std::vector<std::size_t> defaultScalingSizes();

// Exit status 1 when any row could not be described (every row is still timed).
int runScaling(const ScalingArgs& args, const DescriptorOptions& options);

}  // namespace keyturn::app
