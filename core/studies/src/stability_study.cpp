#include "keyturn/studies/stability_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <utility>

#include "keyturn/core/dissimilarity.h"
#include "keyturn/core/error.h"
#include "keyturn/core/median.h"
#include "keyturn/core/parallel_for.h"
#include "keyturn/core/pcl_baselines.h"

namespace keyturn {
namespace {

std::vector<double> normalised(const std::vector<float>& h) {
  std::vector<double> out(h.begin(), h.end());
  const double sum = std::accumulate(out.begin(), out.end(), 0.0);
  if (sum > 0)
    for (double& x : out) x /= sum;
  return out;
}

// Every function's PDF of one view, in the study's function order; empty where it failed.
struct Described {
  int keypoints = 0;
  std::vector<std::vector<double>> pdfs;
};

struct FunctionSlot {
  std::string name;
  bool keypoint;
  std::size_t feature;  // index into the descriptor's features (or kPcl)
  enum Source { Pdf, Scaled, Esf, Vfh } source;
};

std::vector<FunctionSlot> functionSlots(const StabilityOptions& o) {
  std::vector<FunctionSlot> out;
  const auto& fs = o.descriptor.features;
  for (std::size_t f = 0; f < fs.size(); ++f) out.push_back({featureName(fs[f]), isKeypointFeature(fs[f]), f, FunctionSlot::Pdf});
  if (o.descriptor.scaled_twin)
    for (std::size_t f = 0; f < fs.size(); ++f)
      if (!isAngleFeature(fs[f]))
        out.push_back({"s_" + featureName(fs[f]), isKeypointFeature(fs[f]), f, FunctionSlot::Scaled});
  if (o.pcl_descriptors) {
    out.push_back({"esf", false, 0, FunctionSlot::Esf});
    out.push_back({"vfh", false, 0, FunctionSlot::Vfh});
  }
  return out;
}

Described describeAll(const Cloud& cloud, const StabilityOptions& o, const std::vector<FunctionSlot>& slots) {
  const ViewDescriptor d = describeView(cloud, o.descriptor);
  Described out;
  out.keypoints = d.keypointCount();
  std::optional<PointSet> filtered;  // what PCL's descriptors describe (options.pcl_input)
  for (const auto& s : slots) {
    switch (s.source) {
      case FunctionSlot::Pdf: out.pdfs.push_back(d.pdfs[s.feature]); break;
      case FunctionSlot::Scaled: out.pdfs.push_back(d.scaled_pdfs[s.feature]); break;
      case FunctionSlot::Esf:
      case FunctionSlot::Vfh: {
        if (!filtered) {
          if (o.pcl_input == PclInput::Given) {
            filtered = PointSet::fromCloud(cloud);
          } else {
            DescriptorOptions raw = o.descriptor;
            raw.working.enabled = false;
            filtered = prepareView(cloud, raw).points;
          }
        }
        try {
          out.pdfs.push_back(normalised(s.source == FunctionSlot::Esf
                                            ? pclEsfSeeded(*filtered, static_cast<unsigned>(o.descriptor.osada.seed))
                                            : pclVfh(*filtered, o.vfh_normal_radius)));
        } catch (const Error&) {
          out.pdfs.emplace_back();  // PCL found nothing: this function has no distance for the view
        }
        break;
      }
    }
  }
  return out;
}

std::uint64_t drawSeed(std::uint64_t seed, std::size_t view, std::size_t perturbation, int draw) {
  std::uint64_t h = seed * 0x9E3779B97F4A7C15ull;
  for (std::uint64_t x : {static_cast<std::uint64_t>(view), static_cast<std::uint64_t>(perturbation),
                          static_cast<std::uint64_t>(draw)})
    h = (h ^ (x + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2))) * 0xBF58476D1CE4E5B9ull;
  return h;
}

bool comparable(const std::vector<double>& a, const std::vector<double>& b) {
  return !a.empty() && a.size() == b.size();
}

// What one view contributes: its original description and every draw's distances.
struct ViewResult {
  std::optional<Described> original;
  std::string error;
  // [perturbation] → draws: (ΔK, per-function L1, χ²)
  struct Draw {
    int keypoint_change = 0;
    std::vector<double> l1, chi2;
  };
  std::vector<std::vector<Draw>> draws;
  std::vector<int> failed;
};

}  // namespace

double FunctionStability::medianL1(std::size_t p) const { return median(l1[p]); }
double FunctionStability::betweenMedianL1() const { return median(between_l1); }
double FunctionStability::ratio(std::size_t p) const { return medianL1(p) / betweenMedianL1(); }

double FunctionStability::ratioOverall() const {
  std::vector<double> all;
  for (std::size_t p = 0; p < l1.size(); ++p)
    if (!perturbations[p].rigid()) all.insert(all.end(), l1[p].begin(), l1[p].end());
  return median(all) / betweenMedianL1();
}

double FunctionStability::rigidMaxL1() const {
  double worst = std::nan("");
  for (std::size_t p = 0; p < l1.size(); ++p)
    if (perturbations[p].rigid())
      for (double x : l1[p]) worst = std::isnan(worst) ? x : std::max(worst, x);
  return worst;
}

double FunctionStability::rigidShareWithin(double limit) const {
  std::size_t n = 0, within = 0;
  for (std::size_t p = 0; p < l1.size(); ++p)
    if (perturbations[p].rigid())
      for (double x : l1[p])
        if (std::isfinite(x)) ++n, within += x <= limit;
  return n ? static_cast<double>(within) / static_cast<double>(n) : std::nan("");
}

const char* pclInputName(PclInput input) { return input == PclInput::Given ? "given" : "filtered"; }

PclInput pclInputNamed(const std::string& name) {
  if (name == "given") return PclInput::Given;
  if (name == "filtered") return PclInput::Filtered;
  throw Error("PCL's descriptors describe the cloud 'given' or 'filtered', not '" + name + "'");
}

int StabilityStudy::maxAbsKeypointChangeUnder(const std::string& perturbation) const {
  for (std::size_t p = 0; p < perturbations.size(); ++p)
    if (perturbations[p].name == perturbation) {
      int worst = 0;
      for (int k : keypoint_change[p]) worst = std::max(worst, std::abs(k));
      return worst;
    }
  return -1;
}

int StabilityStudy::maxAbsKeypointChange(bool rigid) const {
  int worst = 0;
  for (std::size_t p = 0; p < perturbations.size(); ++p)
    if (perturbations[p].rigid() == rigid)
      for (int k : keypoint_change[p]) worst = std::max(worst, std::abs(k));
  return worst;
}

StabilityStudy runStabilityStudy(const std::vector<StabilityView>& views, const StabilityOptions& o,
                                 const StabilityProgress& progress) {
  if (o.repetitions < 1) throw Error("the stability study needs at least one draw per perturbation");
  const auto slots = functionSlots(o);
  const std::size_t P = o.perturbations.size();
  std::vector<ViewResult> results(views.size());
  progress.begin(views.size());
  std::mutex progress_mutex;
  parallelFor(views.size(), o.jobs, [&](std::size_t v) {
    ViewResult& r = results[v];
    r.draws.resize(P);
    r.failed.assign(P, 0);
    try {
      r.original = describeAll(views[v].cloud, o, slots);
    } catch (const Error& e) {
      r.error = views[v].name + ": " + e.what();
    }
    if (r.original) {
      for (std::size_t p = 0; p < P; ++p)
        for (int k = 0; k < o.repetitions; ++k) {
          const auto moved = perturbView(views[v].cloud, o.perturbations[p], drawSeed(o.seed, v, p, k));
          if (!moved) continue;
          try {
            const Described d = describeAll(*moved, o, slots);
            ViewResult::Draw draw;
            draw.keypoint_change = d.keypoints - r.original->keypoints;
            for (std::size_t f = 0; f < slots.size(); ++f) {
              const auto& a = r.original->pdfs[f];
              const auto& b = d.pdfs[f];
              draw.l1.push_back(comparable(a, b) ? l1Distance(a, b) : std::nan(""));
              draw.chi2.push_back(comparable(a, b) ? chiSquared(a, b) : std::nan(""));
            }
            r.draws[p].push_back(std::move(draw));
          } catch (const Error&) {
            ++r.failed[p];
          }
        }
    }
    std::lock_guard<std::mutex> lock(progress_mutex);
    progress.step();
  });
  progress.end();

  StabilityStudy s;
  s.perturbations = o.perturbations;
  s.repetitions = o.repetitions;
  s.pcl_descriptors = o.pcl_descriptors;
  s.pcl_input = o.pcl_input;
  s.keypoint_change.resize(P);
  s.not_described.assign(P, 0);
  for (const auto& slot : slots) {
    FunctionStability f;
    f.name = slot.name;
    f.keypoint = slot.keypoint;
    f.l1.resize(P);
    f.chi2.resize(P);
    f.perturbations = o.perturbations;
    s.functions.push_back(std::move(f));
  }
  std::vector<std::size_t> described;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const ViewResult& r = results[v];
    if (!r.original) {
      s.errors.push_back(r.error);
      continue;
    }
    described.push_back(v);
    s.views.push_back(views[v].name);
    for (std::size_t p = 0; p < P; ++p) {
      s.not_described[p] += r.failed[p];
      for (const auto& d : r.draws[p]) {
        s.keypoint_change[p].push_back(d.keypoint_change);
        for (std::size_t f = 0; f < slots.size(); ++f) {
          s.functions[f].l1[p].push_back(d.l1[f]);
          s.functions[f].chi2[p].push_back(d.chi2[f]);
        }
      }
    }
  }
  if (described.size() < 2)
    throw Error("the stability study needs at least two views it can describe (" +
                std::to_string(described.size()) + " of " + std::to_string(views.size()) + ")" +
                (s.errors.empty() ? "" : "; first: " + s.errors.front()));
  for (std::size_t a = 0; a < described.size(); ++a)
    for (std::size_t b = a + 1; b < described.size(); ++b) {
      if (views[described[a]].group == views[described[b]].group) continue;
      const auto& pa = results[described[a]].original->pdfs;
      const auto& pb = results[described[b]].original->pdfs;
      for (std::size_t f = 0; f < slots.size(); ++f)
        if (comparable(pa[f], pb[f])) {
          s.functions[f].between_l1.push_back(l1Distance(pa[f], pb[f]));
          s.functions[f].between_chi2.push_back(chiSquared(pa[f], pb[f]));
        }
    }
  return s;
}

namespace {
std::string fixed(double v, int digits = 3) {
  if (!std::isfinite(v)) return "–";
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}
}  // namespace

std::string stabilityMarkdown(const StabilityStudy& s, const std::string& input) {
  std::string md = "# Descriptor stability: " + input + "\n\n" + std::to_string(s.views.size()) + " views, " +
                   std::to_string(s.repetitions) + " draws of each perturbation per view. L1 between a view's PDF and "
                   "its perturbed view's (median over draws); between = median L1 between views of different "
                   "groups; ratio = median non-rigid L1 ÷ between.";
  if (s.pcl_descriptors)
    md += s.pcl_input == PclInput::Given
              ? " PCL's ESF and VFH describe each view's cloud as given (its finite points), as a PCL user computes them."
              : " PCL's ESF and VFH describe each view after keyturn's filter (without the working resolution).";
  // Jitter far below the sensor's noise moves nothing a view shows: its column stands apart from
  // the pooled non-rigid ratio, which also holds resampling and the sensor's own noise.
  std::size_t jitter = s.perturbations.size();
  for (std::size_t p = 0; p < s.perturbations.size(); ++p)
    if (s.perturbations[p].name == "jitter-0.1mm") jitter = p;
  const bool has_jitter = jitter < s.perturbations.size();
  md += "\n\n| function | rigid max L1 | rigid draws with L1 ≤ 0.01 | non-rigid median L1 | between L1 | ratio |";
  md += has_jitter ? " jitter-0.1mm ratio |\n|---|---|---|---|---|---|---|\n" : "\n|---|---|---|---|---|---|\n";
  for (const auto& f : s.functions) {
    std::vector<double> all;
    for (std::size_t p = 0; p < s.perturbations.size(); ++p)
      if (!s.perturbations[p].rigid()) all.insert(all.end(), f.l1[p].begin(), f.l1[p].end());
    md += "| " + f.name + " | " + fixed(f.rigidMaxL1(), 4) + " | " + fixed(100 * f.rigidShareWithin(0.01), 1) + " % | " +
          fixed(median(all)) + " | " +
          fixed(f.betweenMedianL1()) + " | " + fixed(f.ratioOverall()) + " |" +
          (has_jitter ? " " + fixed(f.ratio(jitter)) + " |" : "") + "\n";
  }
  md += "\nRatio per perturbation (median L1 ÷ between):\n\n| function |";
  for (const auto& p : s.perturbations) md += " " + p.name + " |";
  md += "\n|---|";
  for (std::size_t p = 0; p < s.perturbations.size(); ++p) md += "---|";
  md += "\n";
  for (const auto& f : s.functions) {
    md += "| " + f.name + " |";
    for (std::size_t p = 0; p < s.perturbations.size(); ++p) md += " " + fixed(f.ratio(p)) + " |";
    md += "\n";
  }
  md += "\nKeypoint count change K(perturbed) − K(original):\n\n| perturbation | median \\|ΔK\\| | max \\|ΔK\\| | draws | not described |\n|---|---|---|---|---|\n";
  for (std::size_t p = 0; p < s.perturbations.size(); ++p) {
    std::vector<double> a;
    int worst = 0;
    for (int k : s.keypoint_change[p]) a.push_back(std::abs(k)), worst = std::max(worst, std::abs(k));
    md += "| " + s.perturbations[p].name + " | " + fixed(median(a), 1) + " | " + std::to_string(worst) + " | " +
          std::to_string(a.size()) + " | " + std::to_string(s.not_described[p]) + " |\n";
  }
  if (!s.errors.empty()) {
    md += "\nLeft out:\n\n";
    for (const auto& e : s.errors) md += "- " + e + "\n";
  }
  return md;
}

std::string stabilityJson(const StabilityStudy& s, const std::string& input) {
  using nlohmann::json;
  const auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json j;
  j["input"] = input;
  j["views"] = s.views;
  j["repetitions"] = s.repetitions;
  j["errors"] = s.errors;
  if (s.pcl_descriptors) j["pcl_input"] = pclInputName(s.pcl_input);
  for (std::size_t p = 0; p < s.perturbations.size(); ++p) {
    std::vector<double> a;
    int worst = 0;
    for (int k : s.keypoint_change[p]) a.push_back(std::abs(k)), worst = std::max(worst, std::abs(k));
    j["perturbations"].push_back({{"name", s.perturbations[p].name},
                                  {"rigid", s.perturbations[p].rigid()},
                                  {"draws", a.size()},
                                  {"not_described", s.not_described[p]},
                                  {"keypoint_change_median", num(median(a))},
                                  {"keypoint_change_max", worst}});
  }
  for (const auto& f : s.functions) {
    json jf{{"name", f.name},
            {"keypoint", f.keypoint},
            {"between_l1_median", num(f.betweenMedianL1())},
            {"between_chi2_median", num(median(f.between_chi2))},
            {"rigid_l1_max", num(f.rigidMaxL1())},
            {"rigid_share_l1_within_0_01", num(f.rigidShareWithin(0.01))},
            {"ratio", num(f.ratioOverall())}};
    for (std::size_t p = 0; p < s.perturbations.size(); ++p)
      jf["perturbations"][s.perturbations[p].name] = {{"l1_median", num(median(f.l1[p]))},
                                                      {"chi2_median", num(median(f.chi2[p]))},
                                                      {"ratio", num(f.ratio(p))}};
    j["functions"].push_back(jf);
  }
  return j.dump(2);
}

namespace {
// A perturbation's name short enough for an axis label ("rotate-centroid-10deg" → "centroid 10°").
std::string shortLabel(std::string name) {
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"rotate-centroid-", "centroid "},
                                 {"rotate-camera-", "camera "}, {"deg", "°"}, {"depth-round-", "round "},
                                 {"translate-", "move "}}) {
    const auto at = name.find(from);
    if (at != std::string::npos) name.replace(at, from.size(), to);
  }
  return name;
}
}  // namespace

ReportPlots stabilityPlots(const StabilityStudy& s) {
  // Two charts of at most eight lines: the keypoint functions, then the scaled twins and Osada's
  // functions, each beside PCL's ESF and VFH.
  auto chart = [&](const std::string& file, const std::string& title, auto&& wanted) {
    CurvePlot c;
    c.file = file;
    c.title = title;
    c.x_label = "perturbation";
    c.y_label = "PDF change ÷ distance between views";
    c.log_y = true;
    c.y_min = 1e-4;
    c.width = 1200;
    c.height = 720;
    for (const auto& p : s.perturbations) c.x_categories.push_back(shortLabel(p.name));
    for (const auto& f : s.functions) {
      if (!wanted(f)) continue;
      CurveSeries line;
      line.name = f.name;
      for (std::size_t p = 0; p < s.perturbations.size(); ++p) {
        line.x.push_back(static_cast<double>(p));
        // A PDF that did not move at all sits on the axis floor rather than off the log axis.
        line.y.push_back(std::max(f.ratio(p), 1e-4));
      }
      c.series.push_back(std::move(line));
    }
    return c;
  };
  const auto pcl = [](const FunctionStability& f) { return f.name == "esf" || f.name == "vfh"; };
  ReportPlots plots;
  plots.curves.push_back(chart("stability_ratio.png", "Keypoint functions: PDF change ÷ distance between views",
                               [&](const FunctionStability& f) {
                                 return pcl(f) || (f.keypoint && f.name.rfind("s_", 0) != 0);
                               }));
  plots.curves.push_back(chart("stability_ratio_others.png",
                               "Scaled twins and Osada's functions: PDF change ÷ distance between views",
                               [&](const FunctionStability& f) { return pcl(f) || !f.keypoint || f.name.rfind("s_", 0) == 0; }));
  return plots;
}

}  // namespace keyturn
