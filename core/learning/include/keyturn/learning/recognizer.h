#pragma once
// Live recognition of one view with a trained model: the model's own feature
// parameters (its sidecar's spec) → filter → describe → classify. Keeps the
// filtered points and keypoints so a viewer can show what was recognised.
// recognize() may be called from several threads at once.
#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/descriptor.h"
#include "keyturn/learning/model_file.h"

namespace keyturn::learning {

struct Recognition {
  PointSet filtered;                    // the filtered view
  ViewDescriptor descriptor;            // keypoints (K), one PDF per feature the model needs, timings
  std::vector<std::string> block_names; // the model's blocks (without a model: its features)
  std::vector<std::vector<double>> blocks;  // each block's values, in that order
  std::vector<float> features;          // what the classifier saw: the blocks concatenated
  std::vector<float> probabilities;     // one per class, the model's order
  int best = -1;
  Answer answer = Answer::Class;        // Unknown: below an open-set model's threshold (score)
  double score = std::nan("");          // the open-set score; NaN for a closed-set model
  double filter_ms = 0, describe_ms = 0, classify_ms = 0, total_ms = 0;
};

class Recognizer {
 public:
  // Throws keyturn::Error when the model uses a block that is not computed live
  // (the keypoint and Osada blocks are: kpd2 … gkpcd2, d1 … a3, their s_ twins and size).
  explicit Recognizer(Model model, std::string source = "model");
  static Recognizer load(const std::string& dir);
  // Describes views without a model (no classes, recognize() only describes).
  explicit Recognizer(DescriptorOptions options);

  bool hasModel() const { return model_.classifier != nullptr; }
  const ModelInfo& info() const { return model_.info; }
  const std::string& source() const { return source_; }
  const DescriptorOptions& options() const { return options_; }
  std::vector<std::string> blockNames() const;  // Recognition::block_names
  // Throws keyturn::EmptyViewError for a cloud too empty to describe (too few points or
  // keypoints: "no object", empty_view.h), keyturn::Error for other failures: the caller shows
  // it and goes on with the next frame.
  // Without a model it only describes. with_geodesic_paths: the descriptor also hands back
  // its geodesic paths for display (ViewDescriptor::geodesic_paths).
  Recognition recognize(const Cloud& cloud, bool with_geodesic_paths = false) const;
  // The same without classifying (points, descriptor, features only).
  Recognition describe(const Cloud& cloud, bool with_geodesic_paths = false) const;

 private:
  // A block computed live: a feature's PDF, its scale-normalised twin (s_), the size block or the
  // keypoints themselves (kpset).
  struct LiveBlock {
    std::string name;
    std::size_t feature = 0;  // index into options_.features
    bool scaled = false, size = false, keypoint_set = false;
  };
  Model model_;
  std::string source_;
  DescriptorOptions options_;
  std::vector<LiveBlock> live_;
  std::unique_ptr<std::mutex> classify_mutex_ = std::make_unique<std::mutex>();  // one prediction at a time
};

}  // namespace keyturn::learning
