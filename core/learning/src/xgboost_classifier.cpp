#include "xgboost_classifier.h"

#include <xgboost/c_api.h>

#include <cmath>
#include <thread>

#include "keyturn/core/error.h"

namespace keyturn::learning {

namespace {

void check(int rc, const std::string& what) {
  if (rc != 0) throw Error("XGBoost: " + what + ": " + XGBGetLastError());
}

// Owns a DMatrix built from a dense row-major matrix (NaN = missing).
class DMatrix {
 public:
  explicit DMatrix(const Matrix& x) {
    check(XGDMatrixCreateFromMat(x.data(), static_cast<bst_ulong>(x.rows()), static_cast<bst_ulong>(x.cols()),
                                 std::nanf(""), &handle_),
          "cannot build the feature matrix");
  }
  ~DMatrix() { XGDMatrixFree(handle_); }
  DMatrix(const DMatrix&) = delete;
  DMatrix& operator=(const DMatrix&) = delete;
  DMatrixHandle get() const { return handle_; }

 private:
  DMatrixHandle handle_ = nullptr;
};

class XgboostClassifier : public Classifier {
 public:
  explicit XgboostClassifier(const ClassifierParams& p) : params_(p) {}
  ~XgboostClassifier() override { reset(); }

  void fit(const Matrix& x, const std::vector<int>& y, int classes) override {
    if (x.rows() != static_cast<Eigen::Index>(y.size()) || x.rows() == 0)
      throw Error("XGBoost: " + std::to_string(x.rows()) + " feature rows for " + std::to_string(y.size()) + " labels");
    DMatrix data(x);
    const std::vector<float> labels(y.begin(), y.end());
    check(XGDMatrixSetFloatInfo(data.get(), "label", labels.data(), labels.size()), "cannot set labels");
    create(&data);
    classes_ = classes;
    set("objective", "multi:softprob");
    set("num_class", std::to_string(classes));
    set("eta", std::to_string(params_.xgboost.eta));
    set("max_depth", std::to_string(params_.xgboost.max_depth));
    set("subsample", std::to_string(params_.xgboost.subsample));
    set("colsample_bytree", std::to_string(params_.xgboost.colsample_bytree));
    set("seed", std::to_string(params_.seed));
    set("tree_method", "hist");
    const int threads = params_.xgboost.threads > 0 ? params_.xgboost.threads
                                                    : static_cast<int>(std::thread::hardware_concurrency());
    set("nthread", std::to_string(std::max(1, threads)));
    set("verbosity", "0");
    for (int round = 0; round < params_.xgboost.rounds; ++round)
      check(XGBoosterUpdateOneIter(booster_, round, data.get()), "training round " + std::to_string(round));
  }

  Matrix predictProba(const Matrix& x) const override {
    if (!booster_) throw Error("XGBoost: the model is not trained or loaded");
    DMatrix data(x);
    bst_ulong len = 0;
    const float* out = nullptr;
    check(XGBoosterPredict(booster_, data.get(), 0, 0, 0, &len, &out), "prediction failed");
    if (len != static_cast<bst_ulong>(x.rows()) * static_cast<bst_ulong>(classes_))
      throw Error("XGBoost: the model predicts " + std::to_string(len / std::max<bst_ulong>(1, x.rows())) +
                  " classes per view, expected " + std::to_string(classes_));
    return Eigen::Map<const Matrix>(out, x.rows(), classes_);
  }

  void save(const std::string& path) const override {
    check(XGBoosterSaveModel(booster_, path.c_str()), "cannot write " + path);
  }

  void load(const std::string& path, int inputs, int classes) override {
    create(nullptr);
    check(XGBoosterLoadModel(booster_, path.c_str()), "cannot read " + path);
    classes_ = classes;
    bst_ulong features = 0;
    check(XGBoosterGetNumFeature(booster_, &features), path);
    if (static_cast<int>(features) != inputs)
      throw Error(path + ": the XGBoost model takes " + std::to_string(features) + " features, its sidecar says " +
                  std::to_string(inputs));
  }

 private:
  void create(const DMatrix* data) {
    reset();
    DMatrixHandle h = data ? data->get() : nullptr;
    check(XGBoosterCreate(data ? &h : nullptr, data ? 1 : 0, &booster_), "cannot create a booster");
  }
  void set(const char* key, const std::string& value) {
    check(XGBoosterSetParam(booster_, key, value.c_str()), std::string("parameter ") + key + " = " + value);
  }
  void reset() {
    if (booster_) XGBoosterFree(booster_);
    booster_ = nullptr;
  }

  ClassifierParams params_;
  BoosterHandle booster_ = nullptr;
  int classes_ = 0;
};

}  // namespace

std::unique_ptr<Classifier> makeXgboostClassifier(const ClassifierParams& params) {
  return std::make_unique<XgboostClassifier>(params);
}

}  // namespace keyturn::learning
