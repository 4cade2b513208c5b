#include "bench_view.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "keyturn/core/filter.h"
#include "keyturn/core/pcl_baselines.h"
#include "progress.h"
#include "speed_ratio.h"

namespace keyturn::app {
namespace {

struct Spread {
  double median = 0, min = 0, max = 0;
};

Spread spread(std::vector<double> v) {
  Spread s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.min = v.front();
  s.max = v.back();
  const std::size_t m = v.size() / 2;
  s.median = v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  return s;
}

template <typename F>
Spread timeIt(int reps, F&& f) {
  std::vector<double> ms;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return spread(ms);
}

nlohmann::json spreadJson(const Spread& s) {
  return {{"median_ms", s.median}, {"min_ms", s.min}, {"max_ms", s.max}};
}

}  // namespace

nlohmann::json benchView(const std::string& name, const Cloud& cloud, const BenchRuns& runs,
                         const DescriptorOptions& options) {
  using nlohmann::json;
  struct Stage {
    const char* key;
    double StageTimes::*field;
  };
  const Stage stages[] = {{"filter", &StageTimes::filter},     {"resolution", &StageTimes::resolution},
                          {"iss", &StageTimes::iss},           {"kpd", &StageTimes::kpd},
                          {"graph", &StageTimes::graph},       {"gkpd", &StageTimes::geodesic},
                          {"osada", &StageTimes::osada},       {"histogram", &StageTimes::histogram},
                          {"total", &StageTimes::total}};
  std::vector<std::vector<double>> samples(std::size(stages));
  ViewDescriptor d;
  Progress progress("bench " + name, static_cast<std::size_t>(runs.repetitions), runs.progress);
  for (int r = 0; r < runs.repetitions; ++r) {
    d = describeView(cloud, options);
    for (std::size_t s = 0; s < std::size(stages); ++s) samples[s].push_back(d.times.*stages[s].field);
    progress.advance();
  }
  progress.finish();

  json j;
  j["name"] = name;
  j["frame_pixels"] = cloud.size();
  j["input_points"] = d.input_points;
  j["points"] = d.points;
  j["resolution_mm"] = d.resolution * 1000.0;
  j["keypoints"] = d.keypointCount();
  j["repetitions"] = runs.repetitions;
  for (std::size_t s = 0; s < std::size(stages); ++s) {
    const Spread sp = spread(samples[s]);
    j[std::string(stages[s].key) + "_ms"] = sp.median;
    j["stages"][stages[s].key] = spreadJson(sp);
  }

  // PCL on the same filtered cloud with the same radii in metres.
  const Cloud filtered = options.filter ? filterCloud(cloud, options.filter_options) : cloud;
  const PointSet set = PointSet::fromCloud(filtered);
  const double res = d.resolution;
  std::size_t pcl_k = 0;
  const Spread iss = timeIt(runs.pcl_repetitions, [&] {
    pcl_k = pclIssKeypoints(set, options.iss.frame_radius * res, options.iss.nms_radius * res,
                            options.iss.gamma21, options.iss.gamma32, options.iss.min_neighbors)
                .size();
  });
  const Spread esf = timeIt(runs.pcl_repetitions, [&] { pclEsf(set); });
  const Spread vfh = timeIt(runs.pcl_repetitions, [&] { pclVfh(set, options.graph.radius * res); });
  j["pcl_iss_ms"] = iss.median;
  j["pcl_iss_keypoints"] = pcl_k;
  j["pcl_esf_ms"] = esf.median;
  j["pcl_vfh_ms"] = vfh.median;
  j["stages"]["pcl_iss"] = spreadJson(iss);
  j["stages"]["pcl_esf"] = spreadJson(esf);
  j["stages"]["pcl_vfh"] = spreadJson(vfh);
  const double ours = j["iss_ms"].get<double>();
  j["iss_speedup_vs_pcl"] = ours > 0 ? iss.median / ours : 0.0;
  j["iss_vs_pcl"] = speedComparison(ours, iss.median);
  return j;
}

void printViewTable(const nlohmann::json& v) {
  std::printf("\n%s: %zu px, %zu valid → %zu points after filtering, resolution %.2f mm, K = %d keypoints\n",
              v["name"].get<std::string>().c_str(), v["frame_pixels"].get<std::size_t>(),
              v["input_points"].get<std::size_t>(), v["points"].get<std::size_t>(),
              v["resolution_mm"].get<double>(), v["keypoints"].get<int>());
  std::printf("  %-22s %9s %9s %9s   (ms, %d runs, 1 thread)\n", "stage", "median", "min", "max",
              v["repetitions"].get<int>());
  const char* order[] = {"filter", "resolution", "iss", "kpd", "graph", "gkpd", "osada", "histogram", "total"};
  for (const char* k : order) {
    const auto& s = v["stages"][k];
    std::printf("  %-22s %9.3f %9.3f %9.3f\n", k, s["median_ms"].get<double>(), s["min_ms"].get<double>(),
                s["max_ms"].get<double>());
  }
  const double total = v["total_ms"].get<double>();
  const struct { const char* key; const char* label; } pcl[] = {
      {"pcl_iss", "PCL ISSKeypoint3D"}, {"pcl_esf", "PCL ESF"}, {"pcl_vfh", "PCL VFH (+normals)"}};
  for (const auto& p : pcl) {
    const auto& s = v["stages"][p.key];
    std::printf("  %-22s %9.3f %9.3f %9.3f   keyturn total = %.2f× this\n", p.label,
                s["median_ms"].get<double>(), s["min_ms"].get<double>(), s["max_ms"].get<double>(),
                s["median_ms"].get<double>() > 0 ? total / s["median_ms"].get<double>() : 0.0);
  }
  std::printf("  keyturn ISS vs PCL ISSKeypoint3D: %s (median %.3f vs %.3f ms; PCL found %d keypoints)\n",
              v["iss_vs_pcl"].get<std::string>().c_str(), v["iss_ms"].get<double>(),
              v["pcl_iss_ms"].get<double>(), v["pcl_iss_keypoints"].get<int>());
}

}  // namespace keyturn::app
