#include "keyturn/core/view_explanation.h"

#include <cstdio>
#include <sstream>

namespace keyturn {

std::string explainView(const std::string& file, const ViewDescriptor& d) {
  std::ostringstream e;
  char line[512];
  if (d.filter.steps.empty()) {
    e << file << ": not filtered (the filter is off), " << d.input_points << " valid points\n";
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
