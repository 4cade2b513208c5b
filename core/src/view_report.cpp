#include "keyturn/core/view_report.h"

#include <cstdio>
#include <sstream>

namespace keyturn {
namespace {

std::string csvQuote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::string describeCsvHeader(const std::vector<Feature>& features, int bins) {
  std::ostringstream h;
  h << "file,points,keypoints,low_keypoints,unreachable_keypoints,unreachable_pairs,resolution_mm,"
       "input_kind,input_points,crop_removed,jump_edges_removed,support_plane_removed,cluster_removed,"
       "outliers_removed,working_spacing_mm,working_removed,filter_flag";
  for (Feature f : features)
    for (int b = 0; b < bins; ++b) h << ',' << featureName(f) << '_' << b;
  return h.str();
}

std::string describeCsvRow(const std::string& file, const ViewDescriptor& d) {
  std::ostringstream r;
  r.precision(6);
  r << csvQuote(file) << ',' << d.points << ',' << d.keypointCount() << ',' << (d.low_keypoints ? 1 : 0)
    << ',' << d.unreachable_keypoints << ',' << d.unreachable_pairs << ',' << d.resolution * 1000.0;
  r << ',' << (d.filter.steps.empty() ? "unfiltered" : inputKindName(d.filter.kind)) << ',' << d.input_points;
  for (const char* step : {"crop", "jump-edges", "support-plane", "cluster", "outliers"}) {
    std::size_t removed = 0;
    for (const auto& s : d.filter.steps)
      if (s.name == step) removed = s.removed();
    r << ',' << removed;
  }
  r << ',' << d.working.spacing * 1000.0 << ',' << d.working.before - d.working.after << ','
    << csvQuote(d.filter.flaggedSummary());
  for (const auto& pdf : d.pdfs)
    for (double v : pdf) r << ',' << v;
  return r.str();
}

std::string filterExplanation(const std::string& file, const ViewDescriptor& d) {
  std::ostringstream e;
  char line[512];
  if (d.filter.steps.empty()) {
    e << file << ": not filtered (--no-filter), " << d.input_points << " valid points\n";
  } else {
    e << file << ": " << inputKindName(d.filter.kind) << ", " << d.input_points << " valid points\n";
    for (const auto& s : d.filter.steps) {
      if (!s.applied) std::snprintf(line, sizeof line, "  %-18s skipped (%s)\n", s.name.c_str(), s.note.c_str());
      else
        std::snprintf(line, sizeof line, "  %-18s %7zu -> %7zu  (-%zu)%s%s%s\n", s.name.c_str(), s.before, s.after,
                      s.removed(), s.flagged ? "  FLAGGED" : "", s.note.empty() ? "" : "  ", s.note.c_str());
      e << line;
    }
  }
  const auto& w = d.working;
  if (!d.filter.steps.empty()) {
    // The working resolution ran as a filter step; say what spacing it chose.
    if (w.spacing > 0)
      std::snprintf(line, sizeof line, "  (working spacing %.2f mm = extent %.0f mm / samples across%s)\n",
                    w.spacing * 1000, w.extent * 1000, w.subsampled ? "" : "; no denser than that: kept");
    else line[0] = '\0';
  } else if (w.spacing > 0)
    std::snprintf(line, sizeof line, "  %-18s %7zu -> %7zu  (spacing %.2f mm = extent %.0f mm / samples across%s)\n",
                  "working-resolution", w.before, w.after, w.spacing * 1000, w.extent * 1000,
                  w.subsampled ? "" : "; no denser than that: kept");
  else std::snprintf(line, sizeof line, "  %-18s off\n", "working-resolution");
  e << line;
  std::snprintf(line, sizeof line, "  => %zu points, resolution %.2f mm, K = %d keypoints\n", d.points,
                d.resolution * 1000, d.keypointCount());
  e << line;
  return e.str();
}

}  // namespace keyturn
