#include "keyturn/learning/model_file.h"

#include <filesystem>
#include <fstream>
#include <cmath>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>

#include "classifier_params_json.h"
#include "open_set_json.h"
#include "pose_references_json.h"
#include "training_views_json.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/json_error.h"
#include "keyturn/core/json_file.h"
#include "keyturn/core/json_integer.h"

namespace keyturn::learning {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kFormat = "keyturn-model";
constexpr int kVersion = 1;

std::string weightsName(const std::string& kind) { return kind == "xgboost" ? "model.xgb.json" : "model.pt"; }

json toJson(const ModelInfo& m) {
  json j = classifierParamsJson(m.params);
  j.update({{"format", kFormat},
            {"version", kVersion},
            {"classes", m.classes},
            {"blocks", m.blocks},
            {"inputs", m.inputs},
            {"feature_spec", m.spec},
            {"weights", weightsName(m.params.kind)},
            {"class_means", m.class_means}});
  if (m.open_set.enabled()) j["open_set"] = openSetJson(m.open_set);
  if (!m.pose_references.empty())
    j["pose_references"] = poseReferencesJson(m.pose_references, m.open_set.enabled() ? &m.open_set : nullptr);
  if (!m.training_views.empty()) j["training_views"] = trainingViewsJson(m.training_views);
  return j;
}

}  // namespace

ModelInfo parseModelSidecar(const std::string& text, const std::string& source) {
  const json j = parseJson(text, source, JsonShape::Object);
  ModelInfo m;
  const int most = std::numeric_limits<int>::max();
  try {
    if (!j.is_object() || j.value("format", "") != kFormat) throw Error(source + ": not a keyturn model sidecar");
    if (j.at("version") != kVersion)  // compared as JSON numbers: 1e30 is not cast to int
      throw Error(source + ": model format version " + j.at("version").dump() + " is not supported (expected 1)");
    auto& p = m.params;
    p.kind = j.at("classifier").get<std::string>();
    if (p.kind != "xgboost" && p.kind != "mlp" && p.kind != "setnet")
      throw Error(source + ": unknown classifier '" + p.kind + "'");
    p.seed = jsonInteger(j, "seed", std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max(), source);
    const auto& x = j.at("xgboost");
    p.xgboost.eta = x.at("eta").get<double>();
    p.xgboost.max_depth = jsonInteger(x, "max_depth", 0, most, source + ": xgboost");
    p.xgboost.rounds = jsonInteger(x, "rounds", 0, most, source + ": xgboost");
    p.xgboost.subsample = x.at("subsample").get<double>();
    p.xgboost.colsample_bytree = x.at("colsample_bytree").get<double>();
    const auto& n = j.at("mlp");
    p.mlp.hidden = jsonInteger(n, "hidden", 0, most, source + ": mlp");
    p.mlp.layers = jsonInteger(n, "layers", 0, most, source + ": mlp");
    p.mlp.dropout = n.at("dropout").get<double>();
    p.mlp.learning_rate = n.at("learning_rate").get<double>();
    p.mlp.epochs = jsonInteger(n, "epochs", 0, most, source + ": mlp");
    p.mlp.batch = jsonInteger(n, "batch", 0, most, source + ": mlp");
    p.mlp.sigmoid_output = n.at("sigmoid_output").get<bool>();
    if (j.contains("setnet")) {  // models before the set network have no such entry
      const auto& sn = j.at("setnet");
      p.setnet.width = jsonInteger(sn, "width", 1, 1 << 12, source + ": setnet");
      p.setnet.hidden = jsonInteger(sn, "hidden", 1, 1 << 16, source + ": setnet");
      p.setnet.dropout = sn.at("dropout").get<double>();
      p.setnet.learning_rate = sn.at("learning_rate").get<double>();
      p.setnet.epochs = jsonInteger(sn, "epochs", 0, most, source + ": setnet");
      p.setnet.batch = jsonInteger(sn, "batch", 1, most, source + ": setnet");
      p.setnet.min_steps = jsonInteger(sn, "min_steps", 0, 0, most, source + ": setnet");
      p.setnet.keypoint_dropout = sn.value("keypoint_dropout", 0.0);
      p.setnet.jitter_m = sn.value("jitter_m", 0.0);
      if (p.setnet.dropout < 0 || p.setnet.dropout >= 1) throw Error(source + ": setnet: dropout must be in [0, 1)");
    }
    m.classes = j.at("classes").get<std::vector<std::string>>();
    m.blocks = j.at("blocks").get<std::vector<std::string>>();
    m.inputs = jsonInteger(j, "inputs", 0, most, source);
    m.spec = j.at("feature_spec").get<std::map<std::string, std::string>>();
    if (j.contains("class_means")) m.class_means = j.at("class_means").get<std::vector<std::vector<float>>>();
  } catch (const json::exception& e) {
    throw Error(source + ": " + jsonErrorText(e));
  }
  if (m.classes.size() < 2) throw Error(source + ": a model needs at least two classes");
  if (m.inputs <= 0 || m.inputs > 1 << 20) throw Error(source + ": bad input count " + std::to_string(m.inputs));
  if (m.blocks.empty()) throw Error(source + ": the model names no feature blocks");
  if (!m.class_means.empty()) {
    bool ok = m.class_means.size() == m.classes.size();
    for (const auto& row : m.class_means) ok = ok && row.size() == static_cast<std::size_t>(m.inputs);
    if (!ok) throw Error(source + ": class_means must be " + std::to_string(m.classes.size()) + " rows of " +
                         std::to_string(m.inputs) + " values");
  }
  const auto& mp = m.params.mlp;
  if (mp.hidden <= 0 || mp.hidden > 1 << 16 || mp.layers <= 0 || mp.layers > 16 || mp.dropout < 0 || mp.dropout >= 1)
    throw Error(source + ": bad network shape (hidden " + std::to_string(mp.hidden) + ", layers " +
                std::to_string(mp.layers) + ")");
  if (j.contains("open_set") && !j.at("open_set").is_null())
    m.open_set = parseOpenSetJson(j.at("open_set"), m.inputs, static_cast<int>(m.classes.size()), source);
  if (j.contains("pose_references") && !j.at("pose_references").is_null())
    m.pose_references = parsePoseReferencesJson(j.at("pose_references"), m.inputs, static_cast<int>(m.classes.size()),
                                                source, m.open_set.enabled() ? &m.open_set : nullptr);
  // The training views describe the open set's references: without them (a sidecar with its open set
  // taken out, as old models are emulated) they describe nothing, and the model cannot be enrolled into.
  if (j.contains("training_views") && !j.at("training_views").is_null() && keepsReferences(m.open_set.method)) {
    m.training_views = parseTrainingViewsJson(j.at("training_views"), static_cast<std::size_t>(m.open_set.references.rows()),
                                              m.inputs, source);
  }
  return m;
}

void saveModel(const std::string& dir, const Model& model) {
  if (!model.classifier) throw Error(dir + ": no trained classifier to save");
  const fs::path target(dir);
  const fs::path tmp = target.string() + ".tmp";
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) throw Error(tmp.string() + ": cannot create (" + ec.message() + ")");
  const std::string weights = (tmp / weightsName(model.info.params.kind)).string();
  model.classifier->save(weights);
  syncFile(weights);
  // Compact: an open-set or pose-fusion model holds every training view, and indenting them one number
  // a line more than doubled the file (the built-in model 3.6 → 1.6 MB); `jq . model.json` reads it.
  writeFileDurably((tmp / "model.json").string(), toJson(model.info).dump() + "\n");  // syncs the folder too
  fs::remove_all(target, ec);
  fs::rename(tmp, target, ec);
  if (ec) throw Error(dir + ": cannot move the model into place (" + ec.message() + ")");
  syncDirectory(target.has_parent_path() ? target.parent_path().string() : ".");
}

Model loadModel(const std::string& dir) {
  const fs::path sidecar = fs::path(dir) / "model.json";
  std::ifstream in(sidecar, std::ios::binary);
  if (!in) throw Error(dir + ": not a keyturn model (no model.json)");
  const std::string text(std::istreambuf_iterator<char>(in), {});
  Model m;
  m.info = parseModelSidecar(text, sidecar.string());
  const fs::path weights = fs::path(dir) / weightsName(m.info.params.kind);
  if (!fs::is_regular_file(weights)) throw Error(weights.string() + ": missing (the sidecar needs it)");
  m.classifier = makeClassifier(m.info.params);
  m.classifier->load(weights.string(), m.info.inputs, static_cast<int>(m.info.classes.size()));
  return m;
}

std::vector<std::vector<float>> classMeans(const Matrix& x, const std::vector<int>& y, int classes) {
  std::vector<std::vector<double>> sum(static_cast<std::size_t>(classes), std::vector<double>(static_cast<std::size_t>(x.cols()), 0.0));
  std::vector<std::vector<int>> count(sum.size(), std::vector<int>(static_cast<std::size_t>(x.cols()), 0));
  for (Eigen::Index r = 0; r < x.rows(); ++r) {
    const int c = y.at(static_cast<std::size_t>(r));
    if (c < 0 || c >= classes) throw Error("class index " + std::to_string(c) + " outside 0.." + std::to_string(classes - 1));
    for (Eigen::Index k = 0; k < x.cols(); ++k)
      if (std::isfinite(x(r, k))) {
        sum[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] += x(r, k);
        ++count[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)];
      }
  }
  std::vector<std::vector<float>> out(sum.size());
  for (std::size_t c = 0; c < sum.size(); ++c)
    for (std::size_t k = 0; k < sum[c].size(); ++k)
      out[c].push_back(count[c][k] ? static_cast<float>(sum[c][k] / count[c][k]) : 0.f);
  return out;
}

std::vector<std::string> specDifferences(const std::map<std::string, std::string>& model,
                                         const std::map<std::string, std::string>& features) {
  std::vector<std::string> out;
  for (const auto& [k, v] : model) {
    const auto it = features.find(k);
    const std::string have = it == features.end() ? "(not set)" : it->second;
    if (have != v) out.push_back(k + ": model " + v + ", features " + have);
  }
  for (const auto& [k, v] : features)
    if (!model.count(k)) out.push_back(k + ": model (not set), features " + v);
  return out;
}

}  // namespace keyturn::learning
