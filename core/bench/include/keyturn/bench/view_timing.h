#pragma once
// Timing one view through the descriptor chain (median, min, max over repetitions,
// one thread) and PCL's ISSKeypoint3D, ESF and VFH on the same filtered cloud:
// shared by `keyturn bench` per view and by its --scaling run.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/descriptor.h"

namespace keyturn::bench {

// Told of every timed chain run (e.g. to draw a progress line): done is 0 before the first.
using RunProgress = std::function<void(const std::string& label, int done, int total)>;

struct BenchRuns {
  int repetitions = 30;      // describeView runs
  int pcl_repetitions = 10;  // runs of each PCL baseline
  RunProgress progress;      // may be empty
};

// Keys: name, frame_pixels, input_points, points, resolution_mm, keypoints, repetitions,
// STAGE_ms (median wall time) and stages.STAGE.{median,min,max}_ms for filter … total and
// pcl_iss, pcl_esf, pcl_vfh; the same as thread CPU time for total_cpu, pcl_iss_cpu,
// pcl_esf_cpu, pcl_vfh_cpu (also as total_cpu_ms …); pcl_iss_keypoints; iss_speedup_vs_pcl (PCL time / keyturn time)
// and iss_vs_pcl ("2.3× faster"). Throws keyturn::Error when the view cannot be described.
nlohmann::json benchView(const std::string& name, const Cloud& cloud, const BenchRuns& runs,
                         const DescriptorOptions& options);

// A view to time: its name and how to load it (throwing keyturn::Error for an unreadable one),
// or the error already known about it (an argument that named no view).
struct ViewToTime {
  std::string name;
  std::function<Cloud()> load;
  std::string error;
};
using ViewFailure = std::function<void(const std::string& name, const std::string& error)>;

// Every view timed in order; one that fails is an entry {"name", "error"}, told to failed as it
// happens. Keys: the first timed view's at the top level, "views" (every entry) and "failed".
nlohmann::json benchViews(const std::vector<ViewToTime>& views, const BenchRuns& runs,
                          const DescriptorOptions& options, const ViewFailure& failed);

// The per-stage table of one benchView result, as `keyturn bench` prints it.
std::string viewTable(const nlohmann::json& view);

}  // namespace keyturn::bench
