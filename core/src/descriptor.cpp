#include "keyturn/core/descriptor.h"

#include <algorithm>
#include <chrono>

#include "keyturn/core/error.h"
#include "keyturn/core/histogram.h"
#include "keyturn/core/keypoint_functions.h"
#include "keyturn/core/radius_search.h"

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

ViewDescriptor describeView(const Cloud& input, const DescriptorOptions& o) {
  if (o.features.empty()) throw Error("no features requested");
  ViewDescriptor out;
  out.features = o.features;
  const auto start = std::chrono::steady_clock::now();
  StageClock clock;

  if (input.points.empty()) throw Error("empty point cloud");
  out.input_points = input.validCount();
  if (out.input_points == 0) throw Error("no valid points (all NaN or infinite)");
  const Cloud filtered = o.filter ? filterCloud(input, o.filter_options) : input;
  const PointSet set = PointSet::fromCloud(filtered);
  out.points = set.size();
  out.times.filter = clock.lap();
  if (set.size() < 3)
    throw Error("only " + std::to_string(set.size()) + " of " + std::to_string(out.input_points) +
                " points left after filtering");

  const RadiusSearch search(set);
  out.resolution = cloudResolution(set, search);
  out.times.resolution = clock.lap();

  std::vector<int> keypoints;
  const bool need_kp = wants(o.features, isKeypointFeature);
  if (need_kp) {
    keypoints = detectIssKeypoints(set, search, out.resolution, o.iss).keypoints;
    for (int i : keypoints) out.keypoints.push_back(set.points[i]);
    out.times.iss = clock.lap();
    if (out.keypointCount() < o.min_keypoints)
      throw Error("too few keypoints: ISS found " + std::to_string(out.keypointCount()) + " in " +
                  std::to_string(set.size()) + " points (need at least " +
                  std::to_string(o.min_keypoints) + "; move the camera closer or lower the radii)");
    out.low_keypoints = out.keypointCount() < o.low_keypoints;
  }

  std::vector<std::vector<float>> values(o.features.size());
  for (std::size_t f = 0; f < o.features.size(); ++f) {
    switch (o.features[f]) {
      case Feature::KPD2: values[f] = keypointDistances(out.keypoints); break;
      case Feature::KPD3: values[f] = keypointSqrtAreas(out.keypoints); break;
      case Feature::KPA3: values[f] = keypointAngles(out.keypoints); break;
      default: break;
    }
  }
  out.times.kpd = clock.lap();

  if (wants(o.features, isGeodesicFeature)) {
    LocalCompleteGraph graph = buildLocalCompleteGraph(set, search, out.resolution, o.graph);
    out.times.graph = clock.lap();
    int which = 0;
    for (Feature f : o.features) {
      if (f == Feature::GKPD1) which |= kGkpd1;
      if (f == Feature::GKPD2) which |= kGkpd2;
      if (f == Feature::GKPCD2) which |= kGkpcd2;
    }
    GeodesicResult geo = geodesicKeypointDistances(graph, set, keypoints, which);
    out.unreachable_keypoints = geo.unreachable_from_centroid;
    out.unreachable_pairs = geo.unreachable_pairs;
    for (std::size_t f = 0; f < o.features.size(); ++f) {
      if (o.features[f] == Feature::GKPD1) values[f] = std::move(geo.gkpd1);
      if (o.features[f] == Feature::GKPD2) values[f] = std::move(geo.gkpd2);
      if (o.features[f] == Feature::GKPCD2) values[f] = std::move(geo.gkpcd2);
    }
    graph = LocalCompleteGraph();  // free it inside the timed geodesic stage
    out.times.geodesic = clock.lap();
  }

  for (std::size_t f = 0; f < o.features.size(); ++f)
    if (!isKeypointFeature(o.features[f]))
      values[f] = osadaShapeFunction(set.points, osadaOf(o.features[f]), o.osada);
  out.times.osada = clock.lap();

  for (std::size_t f = 0; f < o.features.size(); ++f) {
    HistogramRange range = featureRange(o.features[f], o.histogram);
    if (o.histogram.mode == RangeMode::PerView && !isAngleFeature(o.features[f])) {
      float hi = 0.f;
      for (float v : values[f]) hi = std::max(hi, v);
      range.hi = hi > 0.f ? hi : 1.0;
    }
    out.pdfs.push_back(histogramPdf(values[f], o.histogram.bins, range));
  }
  out.times.histogram = clock.lap();
  out.times.total =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace keyturn
