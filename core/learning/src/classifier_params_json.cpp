#include "classifier_params_json.h"

namespace keyturn::learning {

nlohmann::json classifierParamsJson(const ClassifierParams& p) {
  return {{"classifier", p.kind},
          {"seed", p.seed},
          {"xgboost",
           {{"eta", p.xgboost.eta},
            {"max_depth", p.xgboost.max_depth},
            {"rounds", p.xgboost.rounds},
            {"subsample", p.xgboost.subsample},
            {"colsample_bytree", p.xgboost.colsample_bytree}}},
          {"mlp",
           {{"hidden", p.mlp.hidden},
            {"layers", p.mlp.layers},
            {"dropout", p.mlp.dropout},
            {"learning_rate", p.mlp.learning_rate},
            {"epochs", p.mlp.epochs},
            {"batch", p.mlp.batch},
            {"sigmoid_output", p.mlp.sigmoid_output}}},
          {"setnet",
           {{"width", p.setnet.width},
            {"hidden", p.setnet.hidden},
            {"dropout", p.setnet.dropout},
            {"learning_rate", p.setnet.learning_rate},
            {"epochs", p.setnet.epochs},
            {"batch", p.setnet.batch},
            {"min_steps", p.setnet.min_steps},
            {"keypoint_dropout", p.setnet.keypoint_dropout},
            {"jitter_m", p.setnet.jitter_m}}}};
}

}  // namespace keyturn::learning
