#include "descriptor_options.h"

#include "keyturn/core/error.h"

namespace keyturn::app {

void DescriptorFlags::add(CLI::App& cmd, bool with_features) {
  if (with_features)
    cmd.add_option("--features", features,
                 "Comma-separated keypoint/shape functions: kpd2,kpd3,kpa3,gkpd1,gkpd2,gkpcd2,"
                 "d1,d2,d3,d4,a3 ('+' joins a hybrid, same effect)")
      ->capture_default_str();
  cmd.add_option("--bins", bins, "Histogram bins per feature")->capture_default_str()->check(CLI::Range(2, 4096));
  cmd.add_option("--range", range, "Histogram range rule: fixed (metric, from --extent) or per-view")
      ->capture_default_str();
  cmd.add_option("--extent", extent, "Object extent E in metres for fixed ranges (distances span [0,E])")
      ->capture_default_str()->check(CLI::PositiveNumber);
  cmd.add_flag("--no-filter", no_filter, "Use the cloud as it is (already segmented)");
  cmd.add_flag("--no-plane", no_plane, "Keep the dominant plane");
  cmd.add_option("--max-range", max_range, "Drop points farther than this from the camera (m)")
      ->capture_default_str();
  cmd.add_option("--jump-edge-angle", jump_edge_angle,
                 "Remove pixels whose segment to a neighbour is within this angle of the viewing ray "
                 "(degrees, 0 = off)")
      ->capture_default_str();
  cmd.add_option("--iss-frame", iss_frame, "ISS scatter radius r_frame (× resolution)")->capture_default_str();
  cmd.add_option("--iss-nms", iss_nms, "ISS non-maximum radius (× resolution)")->capture_default_str();
  cmd.add_option("--iss-density", iss_density, "ISS density radius (× resolution)")->capture_default_str();
  cmd.add_option("--graph-radius", graph_radius, "Local complete graph radius (× resolution)")
      ->capture_default_str();
  cmd.add_option("--osada-samples", osada_samples, "Samples per Osada shape distribution")
      ->capture_default_str();
  cmd.add_option("--seed", seed, "Seed of Osada's random sampling")->capture_default_str();
  cmd.add_option("--low-keypoints", low_keypoints, "Flag views with fewer keypoints than this")
      ->capture_default_str();
}

DescriptorOptions DescriptorFlags::toOptions() const {
  DescriptorOptions o;
  o.features = parseFeatureList(features);
  o.histogram.bins = bins;
  o.histogram.mode = parseRangeMode(range);
  o.histogram.extent = extent;
  o.filter = !no_filter;
  o.filter_options.remove_plane = !no_plane;
  o.filter_options.max_range = static_cast<float>(max_range);
  o.filter_options.jump_edge = jump_edge_angle > 0;
  o.filter_options.jump_edge_angle_deg = static_cast<float>(jump_edge_angle);
  if (iss_frame <= 0 || iss_nms <= 0 || iss_density <= 0 || graph_radius <= 0)
    throw Error("radii must be positive multiples of the cloud resolution");
  o.iss.frame_radius = iss_frame;
  o.iss.nms_radius = iss_nms;
  o.iss.density_radius = iss_density;
  o.graph.radius = graph_radius;
  o.osada.samples = osada_samples;
  o.osada.seed = seed;
  o.low_keypoints = low_keypoints;
  return o;
}

}  // namespace keyturn::app
