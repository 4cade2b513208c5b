#include "keyturn/core/view_report.h"

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

}  // namespace keyturn
