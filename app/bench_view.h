#pragma once
// Timing one view through the descriptor chain (median, min, max over repetitions,
// one thread) and PCL's ISSKeypoint3D, ESF and VFH on the same filtered cloud:
// shared by `keyturn bench` per view and by its --scaling run.
#include <nlohmann/json.hpp>
#include <string>

#include "keyturn/core/cloud.h"
#include "keyturn/core/descriptor.h"

namespace keyturn::app {

struct BenchRuns {
  int repetitions = 30;      // describeView runs
  int pcl_repetitions = 10;  // runs of each PCL baseline
  bool progress = true;      // a progress line on stderr
};

// Keys: name, frame_pixels, input_points, points, resolution_mm, keypoints, repetitions,
// STAGE_ms (median wall time) and stages.STAGE.{median,min,max}_ms for filter … total and
// pcl_iss, pcl_esf, pcl_vfh; the same as thread CPU time for total_cpu, pcl_iss_cpu,
// pcl_esf_cpu, pcl_vfh_cpu (also as total_cpu_ms …); pcl_iss_keypoints; iss_speedup_vs_pcl (PCL time / keyturn time)
// and iss_vs_pcl ("2.3× faster"). Throws keyturn::Error when the view cannot be described.
nlohmann::json benchView(const std::string& name, const Cloud& cloud, const BenchRuns& runs,
                         const DescriptorOptions& options);

// The per-stage table of one benchView result on stdout.
void printViewTable(const nlohmann::json& view);

}  // namespace keyturn::app
