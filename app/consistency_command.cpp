// keyturn consistency: how much one object's description changes as it turns
// (the paper's Figs 15–16) — the dissimilarity of the view at each rotation to
// the first view, keypoint functions against Osada's shape functions.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "commands.h"
#include "dataset_features.h"
#include "descriptor_options.h"
#include "keyturn/core/dissimilarity.h"
#include "keyturn/core/error.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/ui/line_chart.h"

namespace keyturn::app {
namespace {

namespace fs = std::filesystem;

struct ConsistencyArgs {
  std::string dataset, object, elevation, out, measure = "bhattacharyya";
  std::string functions = "kpd2,kpd3,kpa3,gkpd2,d2,d3,a3";
  int jobs = 0;
  bool quiet = false;
  DescriptorFlags flags;
};

// "…/aANGLE" → ANGLE in degrees.
double angleOf(const std::string& id) {
  const auto a = id.rfind("/a");
  if (a == std::string::npos) throw Error(id + ": view name has no turntable angle (…/aANGLE)");
  return std::stod(id.substr(a + 2));
}

std::vector<double> pdfOf(const learning::FeatureTable& t, const learning::FeatureRow& r, const std::string& block) {
  const int o = t.offset(block);
  if (o < 0) throw Error("the feature cache has no '" + block + "' block");
  const int n = t.blockSize(block);
  return std::vector<double>(r.values.begin() + o, r.values.begin() + o + n);
}

int runConsistency(const ConsistencyArgs& a) {
  const auto slash = a.object.find('/');
  if (slash == std::string::npos) throw Error("--object " + a.object + ": expected CLASS/INSTANCE");
  const std::string cls = a.object.substr(0, slash), inst = a.object.substr(slash + 1);
  const learning::FeatureTable t = datasetFeatures(a.dataset, a.flags.options, a.jobs, a.quiet);
  const Dissimilarity measure = parseDissimilarity(a.measure);
  std::vector<std::string> functions;
  std::stringstream ss(a.functions);
  for (std::string f; std::getline(ss, f, ',');) functions.push_back(f);

  // Views of the object per elevation, ordered by angle.
  std::map<std::string, std::vector<std::pair<double, const learning::FeatureRow*>>> by_elevation;
  for (const auto& r : t.rows)
    if (r.cls == cls && r.instance == inst && (a.elevation.empty() || r.elevation == a.elevation))
      by_elevation[r.elevation].emplace_back(angleOf(r.id), &r);
  if (by_elevation.empty()) throw Error(a.dataset + ": no views of " + a.object + (a.elevation.empty() ? "" : " at elevation " + a.elevation));

  fs::create_directories(a.out);
  std::ostringstream csv;
  csv << "elevation,angle_deg,keypoints";
  for (const auto& f : functions) csv << ',' << f;
  csv << "\n";
  for (auto& [elev, views] : by_elevation) {
    std::sort(views.begin(), views.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    const auto* first = views.front().second;
    ui::LineChart chart;
    chart.title = a.object + ", elevation " + elev + ": " + a.measure + " dissimilarity to the first view";
    chart.x_label = "turntable angle (°)";
    chart.y_label = a.measure;
    chart.y_min = 0;
    std::vector<ui::Series> series;
    for (const auto& f : functions) series.push_back({f, {}, {}});
    for (const auto& [angle, row] : views) {
      csv << elev << ',' << angle << ',' << row->keypoints;
      for (std::size_t k = 0; k < functions.size(); ++k) {
        const auto p = pdfOf(t, *first, functions[k]), q = pdfOf(t, *row, functions[k]);
        const bool ok = !std::isnan(p.front()) && !std::isnan(q.front());
        const double d = ok ? dissimilarity(measure, p, q) : std::nan("");
        csv << ',' << (ok ? std::to_string(d) : "nan");
        series[k].x.push_back(angle);
        series[k].y.push_back(d);
      }
      csv << "\n";
    }
    chart.series = series;
    ui::saveChartPng(chart, (fs::path(a.out) / ("consistency_e" + elev + ".png")).string());
  }
  const std::string csv_path = (fs::path(a.out) / "consistency.csv").string();
  writeFileDurably(csv_path, csv.str());
  if (!a.quiet) std::cerr << "keyturn consistency: " << a.object << " → " << csv_path << " and consistency_e*.png\n";
  return 0;
}

}  // namespace

Command addConsistencyCommand(CLI::App& app) {
  auto a = std::make_shared<ConsistencyArgs>();
  auto* cmd = app.add_subcommand("consistency", "Dissimilarity of each rotation of an object to its first view (Figs 15-16)");
  cmd->add_option("dataset", a->dataset, "Dataset folder")->required();
  cmd->add_option("--object", a->object, "CLASS/INSTANCE")->required();
  cmd->add_option("--elevation", a->elevation, "Only this elevation label (default: each)");
  cmd->add_option("--functions", a->functions, "Feature blocks to compare")->capture_default_str();
  cmd->add_option("--measure", a->measure, "bhattacharyya, chi2, l1, js or emd")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Output folder (CSV and PNG)")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views when describing");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->flags.add(*cmd, false);
  return {cmd, [a] { return runConsistency(*a); }};
}

}  // namespace keyturn::app
