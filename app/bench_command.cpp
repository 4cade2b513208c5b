// keyturn bench: per-stage time of the descriptor chain (median, min, max over
// repetitions, one thread) with the keypoint count beside it, and PCL's
// ISSKeypoint3D, ESF and VFH timed on the same filtered cloud in the same run.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "descriptor_options.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/pcl_baselines.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/sim/tof_view.h"
#include "progress.h"

namespace keyturn::app {
namespace {

struct BenchArgs {
  std::vector<std::string> files;
  int repetitions = 30;
  int pcl_repetitions = 10;
  bool json = false;
  bool no_builtin = false;
  DescriptorFlags flags;
};

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

Cloud builtinView() {
  const sim::Mesh mug = sim::makeMugMesh();
  sim::TofViewRenderer renderer(mug);
  sim::SceneView view;
  view.turntable_deg = 30.0;
  return renderer.render(view);
}

nlohmann::json benchView(const std::string& name, const Cloud& cloud, const BenchArgs& a,
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
  Progress progress("bench " + name, static_cast<std::size_t>(a.repetitions), !a.json);
  for (int r = 0; r < a.repetitions; ++r) {
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
  j["repetitions"] = a.repetitions;
  for (std::size_t s = 0; s < std::size(stages); ++s) {
    const Spread sp = spread(samples[s]);
    j[std::string(stages[s].key) + "_ms"] = sp.median;
    j["stages"][stages[s].key] = {{"median_ms", sp.median}, {"min_ms", sp.min}, {"max_ms", sp.max}};
  }

  // PCL on the same filtered cloud with the same radii in metres.
  const Cloud filtered = options.filter ? filterCloud(cloud, options.filter_options) : cloud;
  const PointSet set = PointSet::fromCloud(filtered);
  const double res = d.resolution;
  std::size_t pcl_k = 0;
  const Spread iss = timeIt(a.pcl_repetitions, [&] {
    pcl_k = pclIssKeypoints(set, options.iss.frame_radius * res, options.iss.nms_radius * res,
                            options.iss.gamma21, options.iss.gamma32, options.iss.min_neighbors)
                .size();
  });
  const Spread esf = timeIt(a.pcl_repetitions, [&] { pclEsf(set); });
  const Spread vfh = timeIt(a.pcl_repetitions, [&] { pclVfh(set, options.graph.radius * res); });
  j["pcl_iss_ms"] = iss.median;
  j["pcl_iss_keypoints"] = pcl_k;
  j["pcl_esf_ms"] = esf.median;
  j["pcl_vfh_ms"] = vfh.median;
  j["stages"]["pcl_iss"] = {{"median_ms", iss.median}, {"min_ms", iss.min}, {"max_ms", iss.max}};
  j["stages"]["pcl_esf"] = {{"median_ms", esf.median}, {"min_ms", esf.min}, {"max_ms", esf.max}};
  j["stages"]["pcl_vfh"] = {{"median_ms", vfh.median}, {"min_ms", vfh.min}, {"max_ms", vfh.max}};
  j["iss_speedup_vs_pcl"] = j["iss_ms"].get<double>() > 0 ? iss.median / j["iss_ms"].get<double>() : 0.0;
  return j;
}

void printTable(const nlohmann::json& v) {
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
  std::printf("  keyturn ISS is %.1f× faster than PCL ISSKeypoint3D (PCL found %d keypoints)\n",
              v["iss_speedup_vs_pcl"].get<double>(), v["pcl_iss_keypoints"].get<int>());
}

int runBench(const BenchArgs& a) {
  const DescriptorOptions options = a.flags.toOptions();
  nlohmann::json views = nlohmann::json::array();
  if (!a.no_builtin) views.push_back(benchView("builtin:mug", builtinView(), a, options));
  for (const auto& f : a.files) views.push_back(benchView(f, loadCloud(f), a, options));
  if (views.empty()) throw Error("nothing to benchmark (--no-builtin and no files)");
  if (a.json) {
    nlohmann::json out = views[0];
    out["views"] = views;
    std::cout << out.dump(2) << "\n";
  } else {
    for (const auto& v : views) printTable(v);
  }
  return 0;
}

}  // namespace

Command addBenchCommand(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd = app.add_subcommand("bench", "Time every stage of the chain against PCL's ISS, ESF and VFH");
  cmd->add_option("files", args->files, "Extra PCD/PLY views to time (the built-in view always runs first)");
  cmd->add_option("--repetitions,-n", args->repetitions, "Runs per view")->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_option("--pcl-repetitions", args->pcl_repetitions, "Runs of each PCL baseline")
      ->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_flag("--json", args->json, "Print one JSON object (milliseconds) instead of a table");
  cmd->add_flag("--no-builtin", args->no_builtin, "Skip the built-in synthetic SR4000 view");
  args->flags.add(*cmd);
  return {cmd, [args] { return runBench(*args); }};
}

}  // namespace keyturn::app
