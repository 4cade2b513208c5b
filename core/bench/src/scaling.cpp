// Inputs per size (docs/benchmarks.md, "Scaling"): the frame's own object, cut by the
// chain's filter at full resolution, supplies every size up to its point count as a
// seeded uniform random subset (an unorganized segmented object, as a user's crop is);
// larger sizes are the whole frame resampled to that many pixels on the same field of
// view (a lower-resolution sensor of the same scene: still an organized depth frame,
// every pixel a real measurement); 307,200 is the 640 × 480 frame itself.
#include "keyturn/bench/scaling.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/cloud_resample.h"
#include "keyturn/core/error.h"
#include "keyturn/core/filter.h"
#include "keyturn/core/string_format.h"

namespace keyturn::bench {
namespace {

using nlohmann::json;

std::string sizeLabel(std::size_t n) {
  char buf[32];
  if (n >= 1000)
    std::snprintf(buf, sizeof buf, "%.0fk", std::round(n / 1000.0));
  else
    std::snprintf(buf, sizeof buf, "%zu", n);
  return buf;
}

// Left-aligned in `width` columns: printf pads bytes, and "×" is two of them.
std::string padded(const std::string& s, std::size_t width) {
  std::size_t chars = 0;
  for (unsigned char c : s) chars += (c & 0xC0) != 0x80;
  return s + std::string(chars < width ? width - chars : 0, ' ');
}

double num(const json& row, const char* key) {
  return row.contains(key) ? row[key].get<double>() : std::nan("");
}

}  // namespace

std::string scalingTable(const json& out) {
  std::string t;
  appendFormat(t, "%s: %u × %u%s, %zu valid points; its object (cut by the filter): %zu points\n",
              out["source"].get<std::string>().c_str(), out["width"].get<unsigned>(), out["height"].get<unsigned>(),
              out["organized"].get<bool>() ? " organized" : " unorganized", out["valid_points"].get<std::size_t>(),
              out["object_points"].get<std::size_t>());
  appendFormat(t, "median wall-clock ms (CPU: the chain's thread CPU time) over %d runs (PCL: %d runs), 1 thread; object rows: random subsets of the object "
              "(seed %llu); frame rows: the frame resampled to that many pixels\n\n",
              out["repetitions"].get<int>(), out["pcl_repetitions"].get<int>(), out["seed"].get<unsigned long long>());
  appendFormat(t, "%6s  %-26s %7s %8s %5s %9s %9s %8s %8s %8s %8s %9s %5s %9s %9s  %s\n", "size", "input", "valid",
              "filtered", "K", "total", "CPU", "filter", "ISS", "graph", "GKPD", "PCL ISS", "K", "PCL ESF", "total/ESF",
              "keyturn ISS");
  for (const auto& r : out["rows"]) {
    appendFormat(t, "%6s  %s ", sizeLabel(r["size"].get<std::size_t>()).c_str(), padded(r["input"].get<std::string>(), 26).c_str());
    if (r.contains("error")) {
      appendFormat(t, "error: %s\n", r["error"].get<std::string>().c_str());
      continue;
    }
    const double esf = num(r, "pcl_esf_ms");
    appendFormat(t, "%7zu %8zu %5d %9.2f %9.2f %8.2f %8.2f %8.2f %8.2f %9.2f %5d %9.2f %8.1f×  %s\n",
                r["input_points"].get<std::size_t>(), r["points"].get<std::size_t>(), r["keypoints"].get<int>(),
                num(r, "total_ms"), num(r, "total_cpu_ms"), num(r, "filter_ms"), num(r, "iss_ms"), num(r, "graph_ms"), num(r, "gkpd_ms"),
                num(r, "pcl_iss_ms"), r["pcl_iss_keypoints"].get<int>(), esf,
                esf > 0 ? num(r, "total_ms") / esf : 0.0, r["iss_vs_pcl"].get<std::string>().c_str());
  }
  return t;
}

std::vector<std::size_t> defaultScalingSizes() { return {1000, 3000, 10000, 30000, 100000, 307200}; }

json runScaling(const ScalingArgs& a, const DescriptorOptions& options) {
  const auto warn = [&a](const std::string& line) {
    if (a.warn) a.warn(line);
  };
  const Cloud input = loadCloud(a.file, a.depth);
  // The object at full resolution, as the chain's own filter cuts it from the frame;
  // an unorganized input is taken to be an object already.
  Cloud object = input;
  if (input.organized()) {
    try {
      object = filterCloud(input, options.filter_options);
    } catch (const Error& e) {
      warn(a.file + ": cannot cut the object (" + e.what() + "): every size is a resampled frame");
      object = Cloud();
    }
  }
  const std::size_t object_points = object.validCount();

  json out;
  out["source"] = a.file;
  out["width"] = input.width;
  out["height"] = input.height;
  out["organized"] = input.organized();
  out["valid_points"] = input.validCount();
  out["object_points"] = object_points;
  out["seed"] = a.seed;
  out["repetitions"] = a.runs.repetitions;
  out["pcl_repetitions"] = a.runs.pcl_repetitions;
  out["threads"] = 1;
  out["rows"] = json::array();
  int failed = 0;
  for (const std::size_t n : a.sizes) {
    json row;
    char what[96];
    Cloud cloud;
    std::string kind;
    if (n <= object_points) {
      kind = "object";
      std::snprintf(what, sizeof what, "object %zu of %zu", n, object_points);
    } else if (input.organized() && n <= input.size()) {
      kind = "frame";
      cloud = resampleOrganized(input, n);
      std::snprintf(what, sizeof what, "frame %u × %u", cloud.width, cloud.height);
    } else {
      warn(a.file + ": no " + std::to_string(n) + "-point input (the object has " + std::to_string(object_points) +
           " points, the frame " + std::to_string(input.organized() ? input.size() : 0) + " pixels): row left out");
      continue;
    }
    if (kind == "object") cloud = randomSubset(object, n, a.seed);
    const std::string name = a.file + " @ " + sizeLabel(n) + " (" + what + ")";
    try {
      row = benchView(name, cloud, a.runs, options);
    } catch (const Error& e) {
      row["name"] = name;
      row["frame_pixels"] = cloud.size();
      row["error"] = e.what();
      ++failed;
      warn(name + ": " + e.what());
    }
    row["size"] = n;
    row["kind"] = kind;
    row["input"] = what;
    out["rows"].push_back(row);
  }
  if (out["rows"].empty()) throw Error(a.file + ": none of the requested sizes fits this input");
  out["failed"] = failed;
  return out;
}

CurvePlot scalingPlot(const json& out, const std::string& file) {
  CurvePlot chart;
  chart.file = file;
  chart.title = "Time against input size: " + std::filesystem::path(out["source"].get<std::string>()).filename().string() +
                " (1 thread, median of " + std::to_string(out["repetitions"].get<int>()) + " runs)";
  chart.x_label = "input points (object subsets up to " + std::to_string(out["object_points"].get<std::size_t>()) +
                  ", frame pixels above)";
  chart.y_label = "ms (wall clock unless marked)";
  chart.log_x = chart.log_y = true;
  const struct { const char* key; const char* name; } lines[] = {{"total_ms", "keyturn chain"},
                                                               {"iss_ms", "keyturn ISS"},
                                                               {"pcl_iss_ms", "PCL ISSKeypoint3D"},
                                                               {"pcl_esf_ms", "PCL ESF"},
                                                               {"total_cpu_ms", "keyturn chain, CPU time"}};
  for (const auto& l : lines) {
    CurveSeries s{l.name, {}, {}};
    for (const auto& r : out["rows"])
      if (!r.contains("error")) s.x.push_back(r["frame_pixels"].get<double>()), s.y.push_back(r[l.key].get<double>());
    chart.series.push_back(s);
  }
  return chart;
}

}  // namespace keyturn::bench
