// The repeatability report's text files (the plots are drawn by the command's ui).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "keyturn/studies/repeatability_study.h"

namespace keyturn {
namespace {
std::string name(const std::string& file) { return std::filesystem::path(file).filename().string(); }

double rounded(double v, double unit = 1000) { return std::round(v * unit) / unit; }

// Median, min and max of the pairs' overlap.
std::vector<double> overlapStats(const Study& s) {
  std::vector<double> f;
  for (const auto& p : s.pairs) f.push_back(p.overlap);
  if (f.empty()) return {0, 0, 0};
  std::sort(f.begin(), f.end());
  return {f[f.size() / 2], f.front(), f.back()};
}
}  // namespace

std::string studyCsv(const Study& s) {
  std::ostringstream csv;
  csv << "detector,budget,group,model_view,scene_view,rotation_deg,overlap,eps_res,eps_m,model_keypoints,"
         "scene_keypoints,visible,absolute,relative,icp_rms_m\n";
  for (const auto& p : s.pairs) {
    const StudyView &m = s.views[p.model], &v = s.views[p.scene];
    for (const auto& [d, _] : s.detectors)
      for (const char* budget : {"native", "equal"}) {
        const RepeatabilityResult& r = budget[0] == 'n' ? p.native.at(d) : p.equal.at(d);
        for (std::size_t e = 0; e < s.options.eps_res.size(); ++e) {
          csv << detectorName(d) << ',' << budget << ',' << m.group << ',' << name(m.file) << ',' << name(v.file) << ','
              << p.rotation_deg << ',' << p.overlap << ',' << s.options.eps_res[e] << ',' << p.eps_m[e] << ','
              << r.model_keypoints << ',' << r.scene_keypoints << ',' << r.visible << ',' << r.absolute[e] << ','
              << r.relative[e] << ',' << p.icp_rms_m << "\n";
        }
      }
  }
  return csv.str();
}

std::string studyPairsCsv(const Study& s) {
  std::ostringstream csv;
  csv << "group,model_view,scene_view,rotation_deg,overlap,icp_rms_m\n";
  for (const auto& p : s.pairs)
    csv << s.views[p.model].group << ',' << name(s.views[p.model].file) << ',' << name(s.views[p.scene].file) << ','
        << p.rotation_deg << ',' << p.overlap << ',' << p.icp_rms_m << "\n";
  return csv.str();
}

std::string studyMarkdown(const Study& s, const std::string& input) {
  const auto& o = s.options;
  std::ostringstream md;
  const auto ov = overlapStats(s);
  md << "# Keypoint repeatability\n\n" << input << ": " << s.views.size() << " views, " << s.pairs.size() << " pairs ("
     << pairRuleName(o.pairs) << "), mean resolution " << rounded(s.mean_resolution_m * 1000, 100) << " mm"
     << (o.icp ? ", ground truth refined by ICP" : "") << ". Overlap (points within " << o.overlap_radius_res
     << " × resolution of the other view): median " << rounded(ov[0] * 100, 10) << " %, " << rounded(ov[1] * 100, 10)
     << "–" << rounded(ov[2] * 100, 10) << " %.\n\n";
  const std::string budget = o.keypoints > 0 ? "K = " + std::to_string(o.keypoints) : "K = ISS's count per view";
  for (const bool equal : {false, true}) {
    md << (equal ? "Equal budget (" + budget + ", each detector's K most salient)" : std::string("Native keypoints"))
       << ", relative repeatability at ε × resolution:\n\n| detector | mean keypoints |" << (equal ? "" : " detection ms |");
    for (double e : o.eps_res) md << " rel@" << e << " |";
    md << "\n|---|---|" << (equal ? "" : "---|");
    for (std::size_t e = 0; e < o.eps_res.size(); ++e) md << "---|";
    md << "\n";
    for (const auto& [d, S] : s.detectors) {
      md << "| " << detectorName(d) << " | " << rounded(equal ? S.equal_keypoints : S.keypoints, 10) << " |";
      if (!equal) md << ' ' << rounded(S.detection_ms, 10) << " |";
      for (double r : equal ? S.relative_equal : S.relative) md << ' ' << rounded(r) << " |";
      md << "\n";
    }
    md << "\n";
  }
  md << "Absolute repeatability (repeatable keypoints per pair) at ε × resolution, native / equal budget:\n\n"
        "| detector |";
  for (double e : o.eps_res) md << " abs@" << e << " |";
  md << "\n|---|";
  for (std::size_t e = 0; e < o.eps_res.size(); ++e) md << "---|";
  md << "\n";
  for (const auto& [d, S] : s.detectors) {
    md << "| " << detectorName(d) << " |";
    for (std::size_t e = 0; e < o.eps_res.size(); ++e)
      md << ' ' << rounded(S.absolute[e], 10) << " / " << rounded(S.absolute_equal[e], 10) << " |";
    md << "\n";
  }
  md << "\nPlots: `absolute_vs_eps.png`, `relative_vs_eps.png`, `relative_vs_rotation.png` (one colour per detector: native "
        "solid, equal K dashed and marked \"@K\"); every pair, budget and ε in `repeatability.csv`; each pair's rotation and overlap in "
        "`pairs.csv`.\n";
  return md.str();
}

std::string studyJson(const Study& s, const std::string& input) {
  const auto& o = s.options;
  const auto ov = overlapStats(s);
  nlohmann::json j = {{"input", input},
                      {"views", s.views.size()},
                      {"pairs", s.pairs.size()},
                      {"pair_rule", pairRuleName(o.pairs)},
                      {"resolution_mm", s.mean_resolution_m * 1000},
                      {"eps_res", o.eps_res},
                      {"icp", o.icp},
                      {"keypoint_budget", o.keypoints > 0 ? nlohmann::json(o.keypoints) : nlohmann::json("iss")},
                      {"overlap", {{"radius_res", o.overlap_radius_res}, {"median", ov[0]}, {"min", ov[1]},
                                   {"max", ov[2]}, {"mean", s.mean_overlap}}}};
  if (std::isfinite(s.mean_overlap_inverted)) j["overlap"]["mean_inverted"] = s.mean_overlap_inverted;
  if (o.icp) j["icp_rms_mm"] = s.mean_icp_rms_m * 1000;
  for (const auto& [d, S] : s.detectors)
    j["detectors"][detectorName(d)] = {
        {"keypoints", S.keypoints},
        {"detection_ms", S.detection_ms},
        {"absolute", S.absolute},
        {"relative", S.relative},
        {"equal_k", {{"keypoints", S.equal_keypoints}, {"absolute", S.absolute_equal}, {"relative", S.relative_equal}}}};
  return j.dump(2) + "\n";
}

ReportPlots studyPlots(const Study& s) {
  const auto& eps = s.options.eps_res;
  char at[16];
  std::snprintf(at, sizeof at, "%.3g", eps[s.eps_near_2]);
  CurvePlot abs{"absolute_vs_eps.png", "Absolute repeatability", "ε (× resolution)", "repeatable keypoints (mean per pair)", {}};
  CurvePlot rel{"relative_vs_eps.png", "Relative repeatability", "ε (× resolution)", "repeatable / visible", {}, 0.0, 1.0};
  CurvePlot rot{"relative_vs_rotation.png", std::string("Relative repeatability at ε = ") + at + " × resolution",
                "rotation between views (°)", "repeatable / visible", {}, 0.0, 1.0};
  int colour = 0;
  for (const auto& [d, S] : s.detectors) {
    for (const bool equal : {false, true}) {
      const std::string name = detectorName(d) + (equal ? " @K" : "");
      abs.series.push_back({name, eps, equal ? S.absolute_equal : S.absolute, colour, equal});
      rel.series.push_back({name, eps, equal ? S.relative_equal : S.relative, colour, equal});
      CurveSeries by_rotation{name, {}, {}, colour, equal};
      for (const auto& [deg, b] : equal ? S.relative_equal_by_rotation : S.relative_by_rotation) {
        by_rotation.x.push_back(deg);
        by_rotation.y.push_back(b.first / b.second);
      }
      rot.series.push_back(by_rotation);
    }
    ++colour;
  }
  return {{abs, rel, rot}, {}};
}

}  // namespace keyturn
