#pragma once
// The two classifiers of the paper (§5.2): gradient boosting (XGBoost, softmax
// over classes) and a small fully connected network (libtorch). Both are
// seeded, so the same data and parameters give the same model.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace keyturn::learning {

// One row per view (features), row-major so rows hand straight to the libraries.
using Matrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct XgboostParams {
  double eta = 0.3;          // XGBoost's default learning rate
  int max_depth = 6;         // XGBoost's default
  int rounds = 30;
  double subsample = 1.0;
  double colsample_bytree = 1.0;
  // OpenMP threads of a training or prediction; 0: all cores. One by default: on these tables
  // (thousands of rows × 64 columns) a second thread gains little, and libgomp's threads spin at
  // every barrier, so beside any other busy thread (the studio's recognition, a second job) a
  // 2-thread training took 3.8 × the wall time of one (35.7 s against 9.4 s, the built-in model's
  // 6,480 views at load 5); the trees are the same either way (docs/benchmarks.md, "Training").
  int threads = 1;
};

struct MlpParams {
  int hidden = 200;          // §7.2.2: one hidden layer of 200 ReLU units
  int layers = 1;
  double dropout = 0.1;
  double learning_rate = 1e-3;  // Adam
  int epochs = 30;
  int batch = 64;
  bool sigmoid_output = false;  // the paper's Keras output layer; softmax + cross-entropy otherwise
};

// The set network over the keypoints (set_network_classifier.h; features "kpset" first).
struct SetNetParams {
  int width = 32;             // each pair's embedding (two ReLU layers of this width)
  int hidden = 128;           // the head's hidden layer
  double dropout = 0.1;       // in the head
  double learning_rate = 1e-3;  // Adam
  int epochs = 30;
  int batch = 32;
  // At least this many mini-batches in all, however few the views: 30 epochs of mOSD's 37 real
  // objects are 60 batches, and the network answered the majority class (55.3 %); 300: 76.3 %.
  int min_steps = 300;
  double keypoint_dropout = 0;  // training: each keypoint left out of a batch with this probability
  double jitter_m = 0;          // training: each keypoint moved by Gaussian noise of this σ (metres)
};

struct ClassifierParams {
  std::string kind = "xgboost";  // xgboost | mlp | setnet
  std::uint64_t seed = 7;
  XgboostParams xgboost;
  MlpParams mlp;
  SetNetParams setnet;
};

class Classifier {
 public:
  virtual ~Classifier() = default;
  // y holds class indices 0 .. classes - 1.
  virtual void fit(const Matrix& x, const std::vector<int>& y, int classes) = 0;
  // One row of class probabilities per input row.
  virtual Matrix predictProba(const Matrix& x) const = 0;
  // Writes the model's own file(s) at `path` (XGBoost JSON, or a libtorch archive).
  virtual void save(const std::string& path) const = 0;
  virtual void load(const std::string& path, int inputs, int classes) = 0;
};

// Throws keyturn::Error for an unknown kind.
std::unique_ptr<Classifier> makeClassifier(const ClassifierParams& params);

std::vector<int> argmaxRows(const Matrix& probabilities);

}  // namespace keyturn::learning
