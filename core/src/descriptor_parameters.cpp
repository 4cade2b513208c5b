#include "keyturn/core/descriptor_parameters.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "keyturn/core/error.h"

namespace keyturn {
namespace {

using Kind = DescriptorParameter::Kind;

// %g: the form feature caches and sidecars have always used (the cache hash depends on it).
std::string cacheNumberText(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

double parseNumber(const std::string& t) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0' || errno == ERANGE) throw Error("is not a number: '" + t + "'");
  if (!std::isfinite(v)) throw Error("is not a finite number: '" + t + "'");  // strtod takes "nan", "inf"
  return v;
}

template <typename T>
T parseWhole(const std::string& t) {
  char* end = nullptr;
  errno = 0;
  const bool negative = t.find('-') != std::string::npos;
  const auto v = std::is_unsigned_v<T> ? static_cast<long double>(std::strtoull(t.c_str(), &end, 10))
                                       : static_cast<long double>(std::strtoll(t.c_str(), &end, 10));
  if (t.empty() || *end != '\0' || errno == ERANGE || (std::is_unsigned_v<T> && negative) ||
      v < static_cast<long double>(std::numeric_limits<T>::min()) ||
      v > static_cast<long double>(std::numeric_limits<T>::max()))
    throw Error("is not a whole number: '" + t + "'");
  return static_cast<T>(v);
}

// `field` is a generic lambda returning a reference to the field in a DescriptorOptions.
template <typename Field>
DescriptorParameter whole(std::string name, std::string help, Field field, long long lo,
                          long long hi = std::numeric_limits<long long>::max()) {
  using T = std::decay_t<decltype(field(std::declval<DescriptorOptions&>()))>;
  return {std::move(name), std::move(help), Kind::Integer,
          [field](const DescriptorOptions& o) { return std::to_string(field(o)); },
          [field, lo, hi](DescriptorOptions& o, const std::string& t) {
            const T v = parseWhole<T>(t);
            if (static_cast<long double>(v) < lo ||
                (hi != std::numeric_limits<long long>::max() && static_cast<long double>(v) > hi))
              throw Error(hi == std::numeric_limits<long long>::max()
                              ? "must be at least " + std::to_string(lo) + ", not '" + t + "'"
                              : "must be within " + std::to_string(lo) + ".." + std::to_string(hi) + ", not '" + t + "'");
            field(o) = v;
          }};
}

enum class Sign { Any, Positive };

template <typename Field>
DescriptorParameter number(std::string name, std::string help, Field field, Sign sign) {
  using T = std::decay_t<decltype(field(std::declval<DescriptorOptions&>()))>;
  return {std::move(name), std::move(help), Kind::Number,
          [field](const DescriptorOptions& o) { return cacheNumberText(static_cast<double>(field(o))); },
          [field, sign](DescriptorOptions& o, const std::string& t) {
            const double v = parseNumber(t);
            if (sign == Sign::Positive && !(v > 0)) throw Error("must be positive, not '" + t + "'");
            field(o) = static_cast<T>(v);
          }};
}

// Radii of the chain are multiples of the cloud resolution.
template <typename Field>
DescriptorParameter radius(std::string name, std::string help, Field field) {
  return number(std::move(name), std::move(help) + " (× resolution)", field, Sign::Positive);
}

// A number within [0, hi] (the message names the unit, if any), added after specifications were
// first written: a specification without it reads as `absent`.
template <typename Field>
DescriptorParameter within(std::string name, std::string help, Field field, double hi, const std::string& unit,
                           std::string absent) {
  using T = std::decay_t<decltype(field(std::declval<DescriptorOptions&>()))>;
  return {std::move(name), std::move(help), Kind::Number,
          [field](const DescriptorOptions& o) { return cacheNumberText(static_cast<double>(field(o))); },
          [field, hi, unit](DescriptorOptions& o, const std::string& t) {
            const double v = parseNumber(t);
            if (!(v >= 0) || v > hi)
              throw Error("must be within 0.." + cacheNumberText(hi) + unit + ", not '" + t + "'");
            field(o) = static_cast<T>(v);
          },
          std::move(absent)};
}

template <typename Field>
DescriptorParameter onOff(std::string name, std::string help, Field field) {
  return {std::move(name), std::move(help), Kind::Switch,
          [field](const DescriptorOptions& o) -> std::string { return field(o) ? "on" : "off"; },
          [field](DescriptorOptions& o, const std::string& t) {
            if (t != "on" && t != "off") throw Error("must be on or off, not '" + t + "'");
            field(o) = t == "on";
          }};
}

std::vector<DescriptorParameter> makeTable() {
  std::vector<DescriptorParameter> t;
  t.push_back(whole("bins", "Histogram bins per feature", [](auto& o) -> auto& { return o.histogram.bins; },
                    2, 4096));
  t.push_back({"range", "Histogram range rule: fixed (metric, from the extent) or per-view", Kind::Choice,
               [](const DescriptorOptions& o) -> std::string {
                 return o.histogram.mode == RangeMode::Fixed ? "fixed" : "per-view";
               },
               [](DescriptorOptions& o, const std::string& t) {
                 if (t != "fixed" && t != "per-view") throw Error("must be fixed or per-view, not '" + t + "'");
                 o.histogram.mode = t == "fixed" ? RangeMode::Fixed : RangeMode::PerView;
               }});
  t.push_back({"binning",
               "How a value is counted: hard (all in its bin), linear (shared between the two nearest bin "
               "centres: the PDF moves continuously with the values) or quadratic (over three bins, smoother)",
               Kind::Choice, [](const DescriptorOptions& o) -> std::string { return binningName(o.histogram.binning); },
               [](DescriptorOptions& o, const std::string& t) { o.histogram.binning = parseBinning(t); }, "hard"});
  // Issue 30, chosen by measurement on real and simulated views (docs/descriptors.md, "Stability");
  // absent from a specification written before it: unsmoothed PDFs.
  t.push_back(within("pdf_smoothing",
                     "Kernel density PDFs: each length function's PDF smoothed by a Gaussian of this many bins "
                     "(sigma; angles stay as binned), so a keypoint that noise swaps or moves moves its mass to "
                     "the bins around it (0 = off)",
                     [](auto& o) -> auto& { return o.histogram.smoothing; }, 64, " bins", "0"));
  t.push_back(number("extent_m", "Object extent E in metres for fixed ranges (distances span [0,E])",
                     [](auto& o) -> auto& { return o.histogram.extent; }, Sign::Positive));
  t.push_back(onOff("filter", "Use the cloud as it is (already segmented)",
                    [](auto& o) -> auto& { return o.filter; }));
  t.push_back(onOff("plane_removal", "Keep the dominant plane",
                    [](auto& o) -> auto& { return o.filter_options.remove_plane; }));
  t.push_back(number("max_range_m", "Drop points farther than this from the camera (m)",
                     [](auto& o) -> auto& { return o.filter_options.max_range; }, Sign::Any));
  // One number for two fields: 0 turns the step off.
  t.push_back({"jump_edge_deg",
               "Remove pixels whose segment to a neighbour is within this angle of the viewing ray (degrees, 0 = off)",
               Kind::Number,
               [](const DescriptorOptions& o) {
                 return cacheNumberText(o.filter_options.jump_edge ? o.filter_options.jump_edge_angle_deg : 0.0);
               },
               [](DescriptorOptions& o, const std::string& t) {
                 const double v = parseNumber(t);
                 if (v < 0) throw Error("must be 0 (off) or positive, not '" + t + "'");
                 o.filter_options.jump_edge = v > 0;
                 o.filter_options.jump_edge_angle_deg = static_cast<float>(v);
               }});
  t.push_back(radius("iss_frame", "ISS scatter radius r_frame",
                     [](auto& o) -> auto& { return o.iss.frame_radius; }));
  t.push_back(radius("iss_nms", "ISS non-maximum radius", [](auto& o) -> auto& { return o.iss.nms_radius; }));
  t.push_back(radius("iss_density", "ISS density radius",
                     [](auto& o) -> auto& { return o.iss.density_radius; }));
  t.push_back(radius("graph_radius", "Local complete graph radius",
                     [](auto& o) -> auto& { return o.graph.radius; }));
  {
    DescriptorParameter sources = whole(
        "gkpd1_sources",
        "GKPD1's sources: blend the geodesics from this many vertices nearest the centroid, so GKPD1 "
        "changes continuously as the view moves (1 = the nearest vertex alone, before issue 30)",
        [](auto& o) -> auto& { return o.graph.centroid_sources; }, 1, 64);
    sources.absent_means = "1";
    sources.written_when_set = true;  // measured, not the default (docs/descriptors.md, "Stability")
    t.push_back(sources);
  }
  {
    DescriptorParameter floor{
        "curvature_floor",
        "GKPCD2's floor of the curvature factor C = sin(angle between normals), within 0..1: the paper's "
        "0.0001 makes flat parts nearly free, so the normals' noise picks the paths; more follows the surface",
        Kind::Number, [](const DescriptorOptions& o) { return cacheNumberText(o.graph.curvature_epsilon); },
        [](DescriptorOptions& o, const std::string& t) {
          const double v = parseNumber(t);
          if (!(v > 0) || v > 1) throw Error("must be within 0..1 and positive, not '" + t + "'");
          o.graph.curvature_epsilon = v;
        },
        "0.0001"};
    floor.written_when_set = true;  // measured, not the default (docs/descriptors.md, "Stability")
    t.push_back(floor);
  }
  // One number for two fields: 0 describes at the sensor's own spacing.
  t.push_back({"working_samples_across",
               "Working resolution: describe at spacing (view extent / this); 0 = the sensor's own spacing",
               Kind::Number,
               [](const DescriptorOptions& o) { return cacheNumberText(o.working.enabled ? o.working.samples_across : 0.0); },
               [](DescriptorOptions& o, const std::string& t) {
                 const double v = parseNumber(t);
                 if (!(v >= 0) || v > 1e6) throw Error("must be 0 (off) or a positive count up to 1e6, not '" + t + "'");
                 o.working.enabled = v > 0;
                 if (v > 0) o.working.samples_across = v;
               }});
  t.push_back({"working_grid",
               "Working resolution's voxel grid: object (at the view's centroid and principal axes: moving the "
               "view keeps the same points) or camera (the camera frame's, before issue 30)",
               Kind::Choice, [](const DescriptorOptions& o) -> std::string { return voxelAnchorName(o.working.anchor); },
               [](DescriptorOptions& o, const std::string& t) { o.working.anchor = parseVoxelAnchor(t); }, "camera"});
  t.push_back({"working_points",
               "Working resolution's points: means (each voxel's mean) or thinned (the nearest measured points "
               "thinned to the spacing, before issue 30)",
               Kind::Choice, [](const DescriptorOptions& o) -> std::string { return voxelPointsName(o.working.points); },
               [](DescriptorOptions& o, const std::string& t) { o.working.points = parseVoxelPoints(t); }, "thinned"});
  t.push_back(whole("max_keypoints", "Keypoint budget: keep the K most salient ISS keypoints (0 = all)",
                    [](auto& o) -> auto& { return o.iss.max_keypoints; }, 0));
  t.push_back(within("budget_taper",
                     "Weighted keypoint budget: the least salient fraction of the budget weighs less the less salient "
                     "it is, down to 0 at the first keypoint left out (0 = a hard budget)",
                     [](auto& o) -> auto& { return o.iss.budget_taper; }, 1, "", "0"));
  DescriptorParameter fill{"fill_budget",
               "Keypoint budget always reached: when ISS finds fewer local maxima than max_keypoints, the most salient "
               "other points at least the suppression radius apart join them, so sensor noise no longer moves K "
               "(off: K is ISS's count of maxima, at most the budget; issue 49)",
               Kind::Choice, [](const DescriptorOptions& o) -> std::string { return o.iss.fill_budget ? "on" : "off"; },
               [](DescriptorOptions& o, const std::string& t) {
                 if (t != "on" && t != "off") throw Error("must be on or off, not '" + t + "'");
                 o.iss.fill_budget = t == "on";
               },
               "off"};
  // The default since 2026-12-07; written whenever on, so every cache and model made before (no key) reads off.
  fill.written_when_set = true;
  t.push_back(fill);
  DescriptorParameter margin = within(
      "nms_margin",
      "Soft suppression: each ISS maximum weighs its margin over the most salient other point within the suppression "
      "radius (1 - that saliency / its own) divided by this, at most 1, so neighbours that noise swaps weigh about 0 "
      "(0 = every maximum weighs 1; issue 49)",
      [](auto& o) -> auto& { return o.iss.nms_margin; }, 1, "", "0");
  margin.written_when_set = true;  // an option: the default specification, caches and models stay as they were
  t.push_back(margin);
  DescriptorParameter refine{"refine_keypoints",
               "Keypoint refinement: move each keypoint to the most salient measured point within this many ISS "
               "suppression radii of it, before the working resolution (0 = off: keypoints on the working points)",
               Kind::Number,
               [](const DescriptorOptions& o) { return cacheNumberText(o.refine.enabled ? o.refine.window : 0.0); },
               [](DescriptorOptions& o, const std::string& t) {
                 const double v = parseNumber(t);
                 if (!(v >= 0) || v > 1) throw Error("must be 0 (off) or within 0..1, not '" + t + "'");
                 o.refine.enabled = v > 0;
                 if (v > 0) o.refine.window = v;
               },
               "0"};
  refine.written_when_set = true;
  t.push_back(refine);
  DescriptorParameter placement{
      "keypoint_placement",
      "Where each keypoint is placed: means (the voxel mean ISS found it at), nearest (the measured point nearest "
      "it), salient (the most salient measured point near it, coarse to fine from cube moments) or measured (ISS "
      "run on the measured points at the working scale; issue 49)",
      Kind::Choice,
      [](const DescriptorOptions& o) -> std::string { return keypointPlacementName(o.placement.placement); },
      [](DescriptorOptions& o, const std::string& t) { o.placement.placement = parseKeypointPlacement(t); },
      "means"};
  placement.written_when_set = true;
  t.push_back(placement);
  t.push_back(whole("osada_samples", "Samples per Osada shape distribution",
                    [](auto& o) -> auto& { return o.osada.samples; }, 1));
  t.push_back(whole("seed", "Seed of Osada's random sampling (and of the random keypoints and ESF)",
                    [](auto& o) -> auto& { return o.osada.seed; }, 0));
  // A warning's threshold: it changes no feature, so it stays out of the specification.
  DescriptorParameter low = whole("low_keypoints", "Flag views with fewer keypoints than this",
                                  [](auto& o) -> auto& { return o.low_keypoints; }, 0);
  low.in_spec = false;
  t.push_back(low);
  return t;
}

}  // namespace

const std::vector<DescriptorParameter>& descriptorParameters() {
  static const std::vector<DescriptorParameter> table = makeTable();
  return table;
}

const DescriptorParameter& descriptorParameter(const std::string& name) {
  for (const auto& p : descriptorParameters())
    if (p.name == name) return p;
  throw Error("no descriptor parameter named '" + name + "'");
}

std::map<std::string, std::string> parameterSpec(const DescriptorOptions& options) {
  std::map<std::string, std::string> spec;
  for (const auto& p : descriptorParameters()) {
    if (!p.in_spec) continue;
    std::string value = p.get(options);
    if (p.written_when_set && value == p.absent_means) continue;
    spec[p.name] = std::move(value);
  }
  return spec;
}

std::map<std::string, std::string> completedParameterSpec(std::map<std::string, std::string> spec) {
  for (const auto& p : descriptorParameters())
    if (p.in_spec && !p.absent_means.empty()) spec.emplace(p.name, p.absent_means);
  return spec;
}

DescriptorOptions optionsFromParameterSpec(const std::map<std::string, std::string>& spec, const std::string& source) {
  DescriptorOptions o;
  for (const auto& p : descriptorParameters()) {
    if (!p.in_spec) continue;
    const auto it = spec.find(p.name);
    if (it == spec.end() && p.absent_means.empty()) throw Error(source + ": feature spec has no '" + p.name + "'");
    try {
      p.set(o, it == spec.end() ? p.absent_means : it->second);
    } catch (const Error& e) {
      throw Error(source + ": feature spec '" + p.name + "' " + e.what());
    }
  }
  return o;
}

}  // namespace keyturn
