#include "keyturn/learning/consistency.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "keyturn/core/error.h"

namespace keyturn::learning {
namespace {

// "…/aANGLE" → ANGLE in degrees.
double angleOf(const std::string& id) {
  const auto a = id.rfind("/a");
  if (a == std::string::npos) throw Error(id + ": view name has no turntable angle (…/aANGLE)");
  const std::string text = id.substr(a + 2);
  char* end = nullptr;
  const double angle = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(angle))
    throw Error(id + ": view name's turntable angle '" + text + "' is not a number (…/aANGLE)");
  return angle;
}

std::vector<double> pdfOf(const FeatureTable& t, const FeatureRow& r, const std::string& block) {
  const int o = t.offset(block);
  if (o < 0) throw Error("the feature cache has no '" + block + "' block");
  const int n = t.blockSize(block);
  return std::vector<double>(r.values.begin() + o, r.values.begin() + o + n);
}

}  // namespace

std::pair<std::string, std::string> objectParts(const std::string& object) {
  const auto slash = object.find('/');
  if (slash == std::string::npos) throw Error("object " + object + ": expected CLASS/INSTANCE");
  return {object.substr(0, slash), object.substr(slash + 1)};
}

ConsistencyReport consistency(const FeatureTable& t, const ConsistencyQuery& q, const std::string& dataset) {
  const auto [cls, inst] = objectParts(q.object);
  // Views of the object per elevation, ordered by angle.
  std::map<std::string, std::vector<std::pair<double, const FeatureRow*>>> by_elevation;
  for (const auto& r : t.rows)
    if (r.cls == cls && r.instance == inst && (q.elevation.empty() || r.elevation == q.elevation))
      by_elevation[r.elevation].emplace_back(angleOf(r.id), &r);
  if (by_elevation.empty())
    throw Error(dataset + ": no views of " + q.object + (q.elevation.empty() ? "" : " at elevation " + q.elevation));

  ConsistencyReport report;
  std::ostringstream csv;
  csv << "elevation,angle_deg,keypoints";
  for (const auto& f : q.blocks) csv << ',' << f;
  csv << "\n";
  for (auto& [elev, views] : by_elevation) {
    std::sort(views.begin(), views.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    const auto* first = views.front().second;
    CurvePlot chart;
    chart.file = "consistency_e" + elev + ".png";
    chart.title = q.object + ", elevation " + elev + ": " + q.measure_name + " dissimilarity to the first view";
    chart.x_label = "turntable angle (°)";
    chart.y_label = q.measure_name;
    chart.y_min = 0;
    for (const auto& f : q.blocks) chart.series.push_back({f, {}, {}});
    for (const auto& [angle, row] : views) {
      csv << elev << ',' << angle << ',' << row->keypoints;
      for (std::size_t k = 0; k < q.blocks.size(); ++k) {
        const auto p = pdfOf(t, *first, q.blocks[k]), r = pdfOf(t, *row, q.blocks[k]);
        const bool ok = !std::isnan(p.front()) && !std::isnan(r.front());
        const double d = ok ? dissimilarity(q.measure, p, r) : std::nan("");
        char text[32];
        std::snprintf(text, sizeof text, "%.9g", d);  // to_string's 6 decimals write 1e-7 as 0.000000
        csv << ',' << (ok ? text : "nan");
        chart.series[k].x.push_back(angle);
        chart.series[k].y.push_back(d);
      }
      csv << "\n";
    }
    report.plots.curves.push_back(chart);
  }
  report.csv = csv.str();
  return report;
}

}  // namespace keyturn::learning
