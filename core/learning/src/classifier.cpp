#include "keyturn/learning/classifier.h"

#include "keyturn/core/error.h"
#include "keyturn/core/plugin.h"
#include "mlp_classifier.h"
#include "set_network_classifier.h"
#include "xgboost_classifier.h"

namespace keyturn::learning {

// libtorch (0.45 s and 160 MB to load) lives in the plugin "mlp" (both networks), loaded when a network is made.
std::unique_ptr<Classifier> makeMlpClassifier(const ClassifierParams& params) {
  static auto* make = pluginFunction<MakeMlpClassifierFunction>("mlp", "keyturn_mlp_make_classifier");
  return std::unique_ptr<Classifier>(make(params));
}

std::unique_ptr<Classifier> makeSetNetworkClassifier(const ClassifierParams& params) {
  static auto* make = pluginFunction<MakeSetNetworkClassifierFunction>("mlp", "keyturn_setnet_make_classifier");
  return std::unique_ptr<Classifier>(make(params));
}

std::unique_ptr<Classifier> makeClassifier(const ClassifierParams& params) {
  if (params.kind == "xgboost") return makeXgboostClassifier(params);
  if (params.kind == "mlp") return makeMlpClassifier(params);
  if (params.kind == "setnet") return makeSetNetworkClassifier(params);
  throw Error("unknown classifier '" + params.kind + "' (expected xgboost, mlp or setnet)");
}

std::vector<int> argmaxRows(const Matrix& p) {
  std::vector<int> out(static_cast<std::size_t>(p.rows()));
  for (Eigen::Index r = 0; r < p.rows(); ++r) p.row(r).maxCoeff(&out[static_cast<std::size_t>(r)]);
  return out;
}

}  // namespace keyturn::learning
