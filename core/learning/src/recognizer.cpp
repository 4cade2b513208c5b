#include "keyturn/learning/recognizer.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "keyturn/core/empty_view.h"
#include "keyturn/core/error.h"
#include "keyturn/core/features.h"
#include "keyturn/learning/feature_cache.h"
#include "keyturn/learning/feature_spec.h"
#include "keyturn/learning/model_predictions.h"

namespace keyturn::learning {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Recognizer::Recognizer(Model model, std::string source) : model_(std::move(model)), source_(std::move(source)) {
  if (!model_.classifier) throw Error(source_ + ": no classifier");
  options_ = descriptorOptionsFromSpec(model_.info.spec, source_);
  options_.features.clear();
  int inputs = 0;
  for (const auto& b : model_.info.blocks) {
    LiveBlock live{b};
    std::optional<BlockName> parsed;
    try {
      parsed = parseBlockName(b);
    } catch (const Error&) {
    }
    if (!parsed || parsed->kind == BlockName::Peer || parsed->kind == BlockName::RandomTwin)
      throw Error(source_ + ": block '" + b +
                  "' is not computed live (live recognition uses kpd2, kpd3, kpa3, gkpd1, gkpd2, gkpcd2, d1–d4, "
                  "a3, their s_ twins, size and kpset)");
    live.size = parsed->kind == BlockName::Size;
    live.keypoint_set = parsed->kind == BlockName::KeypointSet;
    live.scaled = parsed->kind == BlockName::ScaledTwin;
    if (!live.size && !live.keypoint_set) {
      const auto it = std::find(options_.features.begin(), options_.features.end(), parsed->feature);
      live.feature = static_cast<std::size_t>(it - options_.features.begin());
      if (it == options_.features.end()) options_.features.push_back(parsed->feature);
    }
    options_.scaled_twin = options_.scaled_twin || live.scaled;
    inputs += live.size ? kSizeBlockWidth : live.keypoint_set ? kKeypointSetWidth : options_.histogram.bins;
    live_.push_back(live);
  }
  // The size block or the keypoints alone still need the view described (its points, after the filter).
  if (options_.features.empty()) options_.features.push_back(Feature::KPD2);
  if (inputs != model_.info.inputs)
    throw Error(source_ + ": " + std::to_string(live_.size()) + " blocks of " + std::to_string(inputs) +
                " values do not make the model's " + std::to_string(model_.info.inputs) + " inputs");
}

Recognizer::Recognizer(DescriptorOptions options) : source_("(no model)"), options_(std::move(options)) {
  for (std::size_t f = 0; f < options_.features.size(); ++f) live_.push_back({featureName(options_.features[f]), f});
}

std::vector<std::string> Recognizer::blockNames() const {
  std::vector<std::string> names;
  for (const auto& b : live_) names.push_back(b.name);
  return names;
}

Recognizer Recognizer::load(const std::string& dir) { return Recognizer(loadModel(dir), dir); }

Recognition Recognizer::describe(const Cloud& cloud, bool with_geodesic_paths) const {
  const auto t0 = std::chrono::steady_clock::now();
  Recognition r;
  // Prepare (filter, working resolution) here, then describe those points: they are what a
  // viewer shows, and the keypoint indices point into them.
  if (cloud.validCount() == 0) throw EmptyViewError("no valid points (empty, or all NaN, infinite or beyond 1e+18 m of the origin)");
  PreparedView prepared = prepareView(cloud, options_);
  r.filtered = std::move(prepared.points);
  r.filter_ms = msSince(t0);
  const auto t1 = std::chrono::steady_clock::now();
  r.descriptor =
    describeFilteredPoints(r.filtered, options_, prepared.resolutionFloor(), with_geodesic_paths, &prepared.measured);
  r.describe_ms = msSince(t1);
  r.block_names = blockNames();
  for (const auto& b : live_) {
    r.blocks.push_back(b.size           ? r.descriptor.size.block()
                       : b.keypoint_set ? keypointSetBlock(r.descriptor.keypoints)
                       : b.scaled       ? r.descriptor.scaled_pdfs[b.feature]
                                        : r.descriptor.pdfs[b.feature]);
    for (double v : r.blocks.back()) r.features.push_back(static_cast<float>(v));
  }
  r.total_ms = msSince(t0);
  return r;
}

Recognition Recognizer::recognize(const Cloud& cloud, bool with_geodesic_paths) const {
  const auto t0 = std::chrono::steady_clock::now();
  Recognition r = describe(cloud, with_geodesic_paths);
  if (!hasModel()) return r;
  const auto t2 = std::chrono::steady_clock::now();
  Matrix x(1, static_cast<Eigen::Index>(r.features.size()));
  for (std::size_t k = 0; k < r.features.size(); ++k) x(0, static_cast<Eigen::Index>(k)) = r.features[k];
  Matrix p;
  {
    std::lock_guard<std::mutex> lock(*classify_mutex_);
    p = model_.classifier->predictProba(x);
  }
  const Prediction answer = predictionOf(model_.info, x, p, cameraOf(cloud));
  r.probabilities = answer.probabilities;
  r.best = answer.best;
  r.answer = answer.answer;
  r.score = answer.score;
  r.classify_ms = msSince(t2);
  r.total_ms = msSince(t0);
  return r;
}

}  // namespace keyturn::learning
