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
  cmd.add_option("--samples-across", samples_across,
                 "Working resolution: describe at spacing (view extent / this); 0 = the sensor's own spacing")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_option("--max-keypoints", max_keypoints, "Keypoint budget: keep the K most salient ISS keypoints (0 = all)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_option("--osada-samples", osada_samples, "Samples per Osada shape distribution")
      ->capture_default_str();
  cmd.add_option("--seed", seed, "Seed of Osada's random sampling")->capture_default_str();
  cmd.add_option("--low-keypoints", low_keypoints, "Flag views with fewer keypoints than this")
      ->capture_default_str();
}

learning::FeatureParams DescriptorFlags::params() const {
  learning::FeatureParams p;
  p.bins = bins;
  p.range = range;
  p.extent = extent;
  p.filter = !no_filter;
  p.plane_removal = !no_plane;
  p.max_range = max_range;
  p.jump_edge_angle = jump_edge_angle;
  p.iss_frame = iss_frame;
  p.iss_nms = iss_nms;
  p.iss_density = iss_density;
  p.graph_radius = graph_radius;
  p.samples_across = samples_across;
  p.max_keypoints = max_keypoints;
  p.osada_samples = osada_samples;
  p.seed = seed;
  return p;
}

DescriptorOptions DescriptorFlags::toOptions() const {
  DescriptorOptions o = learning::descriptorOptions(params(), parseFeatureList(features));
  o.low_keypoints = low_keypoints;
  return o;
}

}  // namespace keyturn::app
