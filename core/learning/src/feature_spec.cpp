#include "keyturn/learning/feature_spec.h"

#include <cstdio>
#include <cstdlib>

#include "keyturn/core/error.h"

namespace keyturn::learning {
namespace {

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

class SpecReader {
 public:
  SpecReader(const std::map<std::string, std::string>& spec, const std::string& source) : spec_(spec), source_(source) {}
  const std::string& text(const std::string& key) const {
    const auto it = spec_.find(key);
    if (it == spec_.end()) throw Error(source_ + ": feature spec has no '" + key + "'");
    return it->second;
  }
  double number(const std::string& key) const {
    const std::string& t = text(key);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0') throw Error(source_ + ": feature spec '" + key + "' is not a number: '" + t + "'");
    return v;
  }
  bool onOff(const std::string& key) const {
    const std::string& t = text(key);
    if (t != "on" && t != "off") throw Error(source_ + ": feature spec '" + key + "' must be on or off, not '" + t + "'");
    return t == "on";
  }

 private:
  const std::map<std::string, std::string>& spec_;
  const std::string& source_;
};

}  // namespace

std::map<std::string, std::string> featureSpec(const FeatureParams& f) {
  return {{"cache_version", std::to_string(kFeatureCacheVersion)},
          {"bins", std::to_string(f.bins)},
          {"range", f.range},
          {"extent_m", fmt(f.extent)},
          {"filter", f.filter ? "on" : "off"},
          {"plane_removal", f.plane_removal ? "on" : "off"},
          {"max_range_m", fmt(f.max_range)},
          {"jump_edge_deg", fmt(f.jump_edge_angle)},
          {"keypoints", "iss"},
          {"iss_frame", fmt(f.iss_frame)},
          {"iss_nms", fmt(f.iss_nms)},
          {"iss_density", fmt(f.iss_density)},
          {"graph_radius", fmt(f.graph_radius)},
          {"working_samples_across", fmt(f.samples_across)},
          {"max_keypoints", std::to_string(f.max_keypoints)},
          {"osada_samples", std::to_string(f.osada_samples)},
          {"seed", std::to_string(f.seed)},
          {"normal_radius_m", fmt(kNormalRadius)}};
}

FeatureParams featureParamsFromSpec(const std::map<std::string, std::string>& spec, const std::string& source) {
  const SpecReader r(spec, source);
  if (r.number("cache_version") != kFeatureCacheVersion)
    throw Error(source + ": features of cache version " + r.text("cache_version") + "; this build computes version " +
                std::to_string(kFeatureCacheVersion));
  if (r.text("keypoints") != "iss") throw Error(source + ": keypoints '" + r.text("keypoints") + "' (only iss is known)");
  FeatureParams p;
  p.bins = static_cast<int>(r.number("bins"));
  p.range = r.text("range");
  p.extent = r.number("extent_m");
  p.filter = r.onOff("filter");
  p.plane_removal = r.onOff("plane_removal");
  p.max_range = r.number("max_range_m");
  p.jump_edge_angle = r.number("jump_edge_deg");
  p.iss_frame = r.number("iss_frame");
  p.iss_nms = r.number("iss_nms");
  p.iss_density = r.number("iss_density");
  p.graph_radius = r.number("graph_radius");
  p.samples_across = r.number("working_samples_across");
  p.max_keypoints = static_cast<int>(r.number("max_keypoints"));
  if (!(p.samples_across >= 0) || p.samples_across > 1e6 || p.max_keypoints < 0)
    throw Error(source + ": feature spec working_samples_across or max_keypoints out of range");
  p.osada_samples = static_cast<int>(r.number("osada_samples"));
  p.seed = static_cast<unsigned long long>(r.number("seed"));
  if (p.bins < 2 || p.bins > 4096) throw Error(source + ": feature spec bins " + r.text("bins") + " is outside 2..4096");
  return p;
}

DescriptorOptions descriptorOptions(const FeatureParams& p, const std::vector<Feature>& features) {
  DescriptorOptions o;
  o.features = features;
  o.histogram.bins = p.bins;
  o.histogram.mode = parseRangeMode(p.range);
  o.histogram.extent = p.extent;
  o.filter = p.filter;
  o.filter_options.remove_plane = p.plane_removal;
  o.filter_options.max_range = static_cast<float>(p.max_range);
  o.filter_options.jump_edge = p.jump_edge_angle > 0;
  o.filter_options.jump_edge_angle_deg = static_cast<float>(p.jump_edge_angle);
  if (p.iss_frame <= 0 || p.iss_nms <= 0 || p.iss_density <= 0 || p.graph_radius <= 0)
    throw Error("radii must be positive multiples of the cloud resolution");
  o.iss.frame_radius = p.iss_frame;
  o.iss.nms_radius = p.iss_nms;
  o.iss.density_radius = p.iss_density;
  o.graph.radius = p.graph_radius;
  if (!(p.samples_across >= 0) || p.max_keypoints < 0)
    throw Error("--samples-across and --max-keypoints must be >= 0 (0 = off)");
  o.working.enabled = p.samples_across > 0;
  if (o.working.enabled) o.working.samples_across = p.samples_across;
  o.iss.max_keypoints = p.max_keypoints;
  o.osada.samples = p.osada_samples;
  o.osada.seed = p.seed;
  return o;
}

}  // namespace keyturn::learning
