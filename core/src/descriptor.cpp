#include "keyturn/core/descriptor.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <numeric>
#include <random>

#include "keyturn/core/empty_view.h"
#include "keyturn/core/error.h"
#include "keyturn/core/histogram.h"
#include "keyturn/core/keypoint_functions.h"
#include "keyturn/core/measured_keypoints.h"
#include "keyturn/core/radius_search.h"
#include "keyturn/core/string_format.h"

namespace keyturn {
namespace {

class StageClock {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

OsadaFunction osadaOf(Feature f) {
  switch (f) {
    case Feature::D1: return OsadaFunction::D1;
    case Feature::D2: return OsadaFunction::D2;
    case Feature::D3: return OsadaFunction::D3;
    case Feature::D4: return OsadaFunction::D4;
    default: return OsadaFunction::A3;
  }
}

bool wants(const std::vector<Feature>& fs, bool (*pred)(Feature)) {
  return std::any_of(fs.begin(), fs.end(), pred);
}

}  // namespace

std::vector<double> ViewDescriptor::featureVector() const {
  std::vector<double> v;
  for (const auto& pdf : pdfs) v.insert(v.end(), pdf.begin(), pdf.end());
  return v;
}

PreparedView prepareView(const Cloud& input, const DescriptorOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (input.points.empty()) throw EmptyViewError("empty point cloud");
  PreparedView v;
  v.input_points = input.validCount();
  if (v.input_points == 0) throw EmptyViewError("no valid points (all NaN, infinite or beyond 1e+18 m of the origin)");
  const bool keep_measured =
      (o.refine.enabled || o.placement.placement != KeypointPlacement::VoxelMeans) && o.working.enabled;
  Cloud measured;
  Cloud cloud = o.filter ? filterCloud(input, o.filter_options, &v.filter, &o.working, &v.working,
                                       keep_measured ? &measured : nullptr)
                         : input;
  const std::size_t filtered = cloud.validCount();
  if (filtered < 3) {
    std::string why;
    if (v.filter.too_far)  // made invalid before any step
      appendFormat(why, "%zu beyond %g m of the origin, no measurement", v.filter.too_far, kMaxCoordinate);
    for (const auto& s : v.filter.steps)
      if (s.removed() > 0) why += (why.empty() ? "" : ", ") + s.name + " −" + std::to_string(s.removed());
    throw FilteredAwayError("only " + std::to_string(filtered) + " of " + std::to_string(v.input_points) +
                            " points left after filtering (" + inputKindName(v.filter.kind) + ": " +
                            (why.empty() ? "nothing removed" : why) + ")");
  }
  if (!o.filter) {
    if (keep_measured) measured = cloud;
    subsampleToWorkingResolution(cloud, o.working, &v.working);
  }
  v.points = PointSet::fromCloud(cloud);
  if (keep_measured && v.working.subsampled) v.measured = PointSet::fromCloud(measured);
  if (v.working.off_pixel_rays) v.points.forgetPixels();
  v.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return v;
}

ViewDescriptor describeView(const Cloud& input, const DescriptorOptions& o, PointSet* prepared) {
  if (o.features.empty()) throw Error("no features requested");
  PreparedView v = prepareView(input, o);
  ViewDescriptor out = describeFilteredPoints(v.points, o, v.resolutionFloor(), false, &v.measured);
  out.input_points = v.input_points;
  out.filter = std::move(v.filter);
  out.working = v.working;
  out.times.filter = v.ms;
  out.times.total += v.ms;
  if (prepared) *prepared = std::move(v.points);
  return out;
}

ViewDescriptor describeFilteredPoints(const PointSet& set, const DescriptorOptions& o, double min_resolution,
                                      bool with_geodesic_paths, const PointSet* measured) {
  if (o.features.empty()) throw Error("no features requested");
  ViewDescriptor out;
  out.features = o.features;
  const auto start = std::chrono::steady_clock::now();
  StageClock clock;
  out.input_points = set.size();
  out.points = set.size();
  if (set.size() < 3) throw EmptyViewError("only " + std::to_string(set.size()) + " points left after filtering");

  RadiusSearch search(set);
  out.resolution = std::max(cloudResolution(set, search), min_resolution);
  // One search at the largest radius any stage asks for; every later query is a row scan.
  const double largest = std::max({o.iss.density_radius, o.iss.frame_radius, o.iss.nms_radius, o.graph.radius});
  search.cacheNeighbourhoods(static_cast<float>(largest * out.resolution));
  out.times.resolution = clock.lap();

  std::vector<int> keypoints;
  const bool need_kp = wants(o.features, isKeypointFeature);
  if (need_kp) {
    if (!o.refine.enabled && o.placement.placement == KeypointPlacement::Measured && measured && measured->size() >= 2) {
      MeasuredKeypoints m = detectKeypointsOnMeasuredPoints(*measured, set, out.resolution, o.iss);
      keypoints = std::move(m.vertex);
      out.keypoints = std::move(m.positions);
      out.keypoint_weight = std::move(m.weight);
      out.filled_keypoints = m.filled;
    } else {
      IssResult iss = detectIssKeypoints(set, search, out.resolution, o.iss);
      keypoints = std::move(iss.keypoints);
      out.keypoint_weight = std::move(iss.weight);
      out.filled_keypoints = iss.filled;
      for (int i : keypoints) out.keypoints.push_back(set.points[i]);
    }
    out.keypoint_index = keypoints;
    if (o.refine.enabled && measured && measured->size() >= 2)
      out.keypoints = refineKeypointsOnMeasuredPoints(*measured, out.keypoints, out.resolution, o.iss, o.refine);
    else if (measured && measured->size() >= 2)
      out.keypoints = placeKeypoints(*measured, out.keypoints, out.resolution, o.iss, o.placement);
    out.times.iss = clock.lap();
    // A filled budget does not hide a view without salient structure: the checks count ISS's maxima.
    const int maxima = out.keypointCount() - out.filled_keypoints;
    if (maxima < o.min_keypoints)
      throw EmptyViewError("too few keypoints: ISS found " + std::to_string(maxima) + " in " +
                  std::to_string(set.size()) + " points (need at least " +
                  std::to_string(o.min_keypoints) + "; move the camera closer or lower the radii)");
    out.low_keypoints = maxima < o.low_keypoints;
  }

  LocalCompleteGraph graph;
  const bool need_graph = wants(o.features, isGeodesicFeature);
  const bool paths = with_geodesic_paths && need_kp;
  if (need_graph || paths) {
    GraphOptions go = o.graph;
    go.curvature_weights = std::find(o.features.begin(), o.features.end(), Feature::GKPCD2) != o.features.end();
    graph = buildLocalCompleteGraph(set, search, out.resolution, go);
  }
  out.times.graph = clock.lap();

  out.size = viewSize(set.points);  // the scaled twins' unit and the size block
  // Keypoint functions, geodesics, Osada's functions and PDFs for one keypoint set.
  // kp_weight: one per keypoint (the weighted budget), or null: each value's weight follows from it.
  // kp: the keypoints' positions (refined ones need not be points of the set; the geodesics start
  // from kp_index, the graph's vertices the keypoints were found at).
  auto pdfsFor = [&](const std::vector<Eigen::Vector3f>& kp, const std::vector<int>& kp_index,
                     const std::vector<double>* kp_weight, bool with_shape_functions, GeodesicResult* geo_out,
                     std::vector<std::vector<double>>* scaled_out) {
    std::vector<std::vector<float>> values(o.features.size()), weights(o.features.size());
    for (std::size_t f = 0; f < o.features.size(); ++f) {
      switch (o.features[f]) {
        case Feature::KPD2:
          values[f] = keypointDistances(kp);
          if (kp_weight) weights[f] = pairWeights(*kp_weight);
          break;
        case Feature::KPD3:
          values[f] = keypointSqrtAreas(kp);
          if (kp_weight) weights[f] = tripleWeights(*kp_weight);
          break;
        case Feature::KPA3: break;  // binned as it is computed, below
        default: break;
      }
    }
    out.times.kpd += clock.lap();
    if (need_graph) {
      int which = 0;
      for (Feature f : o.features) {
        if (f == Feature::GKPD1) which |= kGkpd1;
        if (f == Feature::GKPD2) which |= kGkpd2;
        if (f == Feature::GKPCD2) which |= kGkpcd2;
      }
      GeodesicResult geo = geodesicKeypointDistances(graph, set, kp_index, which, kp_weight, o.graph.centroid_sources);
      for (std::size_t f = 0; f < o.features.size(); ++f) {
        if (o.features[f] == Feature::GKPD1) values[f] = std::move(geo.gkpd1), weights[f] = std::move(geo.gkpd1_weight);
        if (o.features[f] == Feature::GKPD2) values[f] = std::move(geo.gkpd2), weights[f] = std::move(geo.gkpd2_weight);
        if (o.features[f] == Feature::GKPCD2) values[f] = std::move(geo.gkpcd2), weights[f] = std::move(geo.gkpcd2_weight);
      }
      if (geo_out) *geo_out = std::move(geo);
      out.times.geodesic += clock.lap();
    }
    for (std::size_t f = 0; f < o.features.size(); ++f)
      if (!isKeypointFeature(o.features[f]) && with_shape_functions)
        values[f] = osadaShapeFunction(set.points, osadaOf(o.features[f]), o.osada);
    out.times.osada += clock.lap();
    std::vector<std::vector<double>> pdfs;
    for (std::size_t f = 0; f < o.features.size(); ++f) {
      if (!with_shape_functions && !isKeypointFeature(o.features[f])) {
        pdfs.emplace_back();
        continue;
      }
      HistogramRange range = featureRange(o.features[f], o.histogram);
      if (o.features[f] == Feature::KPA3) {  // 3·C(K,3) angles: binned without most of their arccos
        pdfs.push_back(keypointAnglePdf(kp, o.histogram.bins, range, o.histogram.binning, kp_weight));
        if (scaled_out) scaled_out->push_back(pdfs.back());
        continue;
      }
      if (o.histogram.mode == RangeMode::PerView && !isAngleFeature(o.features[f])) {
        float hi = 0.f;
        for (float v : values[f]) hi = std::max(hi, v);
        range.hi = hi > 0.f ? hi : 1.0;
      }
      const std::vector<float>* w = kp_weight && isKeypointFeature(o.features[f]) ? &weights[f] : nullptr;
      pdfs.push_back(histogramPdf(values[f], o.histogram.bins, range, nullptr, o.histogram.binning, w));
      if (scaled_out) {
        HistogramOptions scaled = o.histogram;
        scaled.extent = kScaledExtent * std::max(out.size.rms_radius, 1e-9);
        scaled_out->push_back(isAngleFeature(o.features[f])
                                  ? pdfs.back()
                                  : histogramPdf(values[f], o.histogram.bins, featureRange(o.features[f], scaled),
                                                 nullptr, o.histogram.binning, w));
      }
    }
    // Kernel density estimates of the lengths' PDFs. The angles' stay as binned: their 3·C(K,3)
    // values are already dense, smoothing steadied KPA3 little and cost it accuracy
    // (docs/descriptors.md, "Kernel density PDFs").
    if (o.histogram.smoothing > 0)
      for (std::size_t f = 0; f < pdfs.size(); ++f) {
        if (isAngleFeature(o.features[f])) continue;
        smoothPdf(pdfs[f], o.histogram.smoothing);
        if (scaled_out) smoothPdf((*scaled_out)[f], o.histogram.smoothing);
      }
    out.times.histogram += clock.lap();
    return pdfs;
  };

  GeodesicResult geo;
  out.pdfs = pdfsFor(out.keypoints, keypoints, out.keypoint_weight.empty() ? nullptr : &out.keypoint_weight, true, &geo,
                     o.scaled_twin ? &out.scaled_pdfs : nullptr);
  out.unreachable_keypoints = geo.unreachable_from_centroid;
  out.unreachable_pairs = geo.unreachable_pairs;
  if (paths) {
    out.geodesic_paths = centroidGeodesicPolylines(graph, set, keypoints);
    out.times.geodesic += clock.lap();
  }
  if (o.random_keypoints_twin && need_kp) {
    // The same number of keypoints drawn uniformly from the filtered points:
    // what the keypoint functions give without ISS's choice of points.
    std::vector<int> all(set.size());
    std::iota(all.begin(), all.end(), 0);
    std::vector<int> drawn;
    std::sample(all.begin(), all.end(), std::back_inserter(drawn), keypoints.size(), std::mt19937_64(o.random_seed));
    std::vector<Eigen::Vector3f> at;
    for (int i : drawn) at.push_back(set.points[i]);
    out.random_keypoint_pdfs = pdfsFor(at, drawn, nullptr, false, nullptr, nullptr);
  }
  graph = LocalCompleteGraph();
  out.times.total =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace keyturn
