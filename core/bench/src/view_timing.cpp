#include "keyturn/bench/view_timing.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <vector>

#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/pcl_baselines.h"
#include "keyturn/bench/speed_ratio.h"
#include "keyturn/core/string_format.h"
#include "spread.h"

namespace keyturn::bench {
namespace {

// CPU time of the calling thread: on a shared, loaded machine the wall clock also counts
// the time other processes held the core; this does not.
double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

struct Timed {
  Spread wall, cpu;
};

template <typename F>
Timed timeIt(int reps, F&& f) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < reps; ++r) {
    const double c0 = threadCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    f();
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(threadCpuMs() - c0);
  }
  return {spread(wall), spread(cpu)};
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
  std::vector<double> cpu;
  ViewDescriptor d;
  const std::string label = "bench " + name;
  if (runs.progress) runs.progress(label, 0, runs.repetitions);
  for (int r = 0; r < runs.repetitions; ++r) {
    const double c0 = threadCpuMs();
    d = describeView(cloud, options);
    cpu.push_back(threadCpuMs() - c0);
    for (std::size_t s = 0; s < std::size(stages); ++s) samples[s].push_back(d.times.*stages[s].field);
    if (runs.progress) runs.progress(label, r + 1, runs.repetitions);
  }

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
  const Spread total_cpu = spread(cpu);
  j["total_cpu_ms"] = total_cpu.median;
  j["stages"]["total_cpu"] = spreadJson(total_cpu);

  // PCL on the points keyturn's ISS sees (filtered, at the working resolution), same radii in metres.
  const PointSet set = prepareView(cloud, options).points;
  const double res = d.resolution;
  std::size_t pcl_k = 0;
  const Timed iss = timeIt(runs.pcl_repetitions, [&] {
    pcl_k = pclIssKeypoints(set, options.iss.frame_radius * res, options.iss.nms_radius * res,
                            options.iss.gamma21, options.iss.gamma32, options.iss.min_neighbors)
                .size();
  });
  const Timed esf = timeIt(runs.pcl_repetitions, [&] { pclEsf(set); });
  const Timed vfh = timeIt(runs.pcl_repetitions, [&] { pclVfh(set, options.graph.radius * res); });
  j["pcl_iss_keypoints"] = pcl_k;
  const std::pair<const char*, const Timed*> pcl[] = {{"pcl_iss", &iss}, {"pcl_esf", &esf}, {"pcl_vfh", &vfh}};
  for (const auto& [key, t] : pcl) {
    j[std::string(key) + "_ms"] = t->wall.median;
    j[std::string(key) + "_cpu_ms"] = t->cpu.median;
    j["stages"][key] = spreadJson(t->wall);
    j["stages"][std::string(key) + "_cpu"] = spreadJson(t->cpu);
  }
  const double ours = j["iss_ms"].get<double>();
  j["iss_speedup_vs_pcl"] = ours > 0 ? iss.wall.median / ours : 0.0;
  j["iss_vs_pcl"] = speedComparison(ours, iss.wall.median);
  return j;
}

nlohmann::json benchViews(const std::vector<ViewToTime>& views, const BenchRuns& runs,
                          const DescriptorOptions& options, const ViewFailure& failed) {
  nlohmann::json all = nlohmann::json::array();
  int failures = 0;
  for (const auto& v : views) {
    std::string error = v.error;
    if (error.empty()) {
      try {
        all.push_back(benchView(v.name, v.load(), runs, options));
        continue;
      } catch (const Error& e) {
        const std::string prefix = v.name + ": ", msg = e.what();
        error = msg.rfind(prefix, 0) == 0 ? msg.substr(prefix.size()) : msg;  // loadCloud's messages name the file
      } catch (const std::exception& e) {
        error = std::string("unexpected failure: ") + e.what();
      }
    }
    if (failed) failed(v.name, error);
    all.push_back({{"name", v.name}, {"error", error}});
    ++failures;
  }
  nlohmann::json out = nlohmann::json::object();
  for (const auto& v : all)
    if (!v.contains("error")) {
      out = v;
      break;
    }
  out["views"] = all;
  out["failed"] = failures;
  return out;
}

std::string viewTable(const nlohmann::json& v) {
  std::string t;
  appendFormat(t, "\n%s: %zu px, %zu valid → %zu points after filtering, resolution %.2f mm, K = %d keypoints\n",
              v["name"].get<std::string>().c_str(), v["frame_pixels"].get<std::size_t>(),
              v["input_points"].get<std::size_t>(), v["points"].get<std::size_t>(),
              v["resolution_mm"].get<double>(), v["keypoints"].get<int>());
  appendFormat(t, "  %-22s %9s %9s %9s   (ms, %d runs, 1 thread)\n", "stage", "median", "min", "max",
              v["repetitions"].get<int>());
  const char* order[] = {"filter", "resolution", "iss", "kpd", "graph", "gkpd", "osada", "histogram", "total"};
  for (const char* k : order) {
    const auto& s = v["stages"][k];
    appendFormat(t, "  %-22s %9.3f %9.3f %9.3f\n", k, s["median_ms"].get<double>(), s["min_ms"].get<double>(),
                s["max_ms"].get<double>());
  }
  const auto& c = v["stages"]["total_cpu"];
  appendFormat(t, "  %-22s %9.3f %9.3f %9.3f   (this thread's CPU time: what a loaded machine's wall clock hides)\n",
              "total, CPU time", c["median_ms"].get<double>(), c["min_ms"].get<double>(), c["max_ms"].get<double>());
  const double total = v["total_ms"].get<double>();
  const struct { const char* key; const char* label; } pcl[] = {
      {"pcl_iss", "PCL ISSKeypoint3D"}, {"pcl_esf", "PCL ESF"}, {"pcl_vfh", "PCL VFH (+normals)"}};
  for (const auto& p : pcl) {
    const auto& s = v["stages"][p.key];
    appendFormat(t, "  %-22s %9.3f %9.3f %9.3f   keyturn total = %.2f× this\n", p.label,
                s["median_ms"].get<double>(), s["min_ms"].get<double>(), s["max_ms"].get<double>(),
                s["median_ms"].get<double>() > 0 ? total / s["median_ms"].get<double>() : 0.0);
  }
  appendFormat(t, "  keyturn ISS vs PCL ISSKeypoint3D: %s (median %.3f vs %.3f ms; PCL found %d keypoints)\n",
              v["iss_vs_pcl"].get<std::string>().c_str(), v["iss_ms"].get<double>(),
              v["pcl_iss_ms"].get<double>(), v["pcl_iss_keypoints"].get<int>());
  return t;
}

}  // namespace keyturn::bench
