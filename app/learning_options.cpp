#include "learning_options.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "keyturn/core/error.h"
#include "keyturn/learning/turn_fusion.h"

namespace keyturn::app {

std::pair<int, int> parseShard(const std::string& text) {
  int shard = 0, shards = 1;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> shard >> slash >> shards) || slash != '/' || !in.eof())
    throw Error("--shard " + text + ": expected I/N, e.g. 3/16");
  if (shards < 1 || shard < 1 || shard > shards) throw Error("--shard " + text + ": expected I/N with 1 <= I <= N");
  return {shard - 1, shards};
}

void addClassifierOptions(CLI::App& cmd, learning::ClassifierParams& p) {
  cmd.add_option("--model-seed", p.seed, "Seed of the classifiers")->capture_default_str();
  cmd.add_option("--eta", p.xgboost.eta, "XGBoost learning rate")->capture_default_str();
  cmd.add_option("--max-depth", p.xgboost.max_depth, "XGBoost tree depth")->capture_default_str();
  cmd.add_option("--rounds", p.xgboost.rounds, "XGBoost boosting rounds")->capture_default_str();
  cmd.add_option("--subsample", p.xgboost.subsample, "XGBoost row subsampling")->capture_default_str();
  cmd.add_option("--colsample", p.xgboost.colsample_bytree, "XGBoost feature subsampling per tree")
      ->capture_default_str();
  cmd.add_option("--hidden", p.mlp.hidden, "Network: units per hidden layer")->capture_default_str();
  cmd.add_option("--layers", p.mlp.layers, "Network: hidden layers")->capture_default_str();
  cmd.add_option("--dropout", p.mlp.dropout, "Network: dropout after each hidden layer")->capture_default_str();
  cmd.add_option("--epochs", p.mlp.epochs, "Network: training epochs (Adam)")->capture_default_str();
  cmd.add_option("--learning-rate", p.mlp.learning_rate, "Network: Adam learning rate")->capture_default_str();
  cmd.add_option("--batch", p.mlp.batch, "Network: mini-batch size")->capture_default_str();
  cmd.add_flag("--sigmoid-output", p.mlp.sigmoid_output,
               "Network: the paper's sigmoid output layer (default: softmax with cross-entropy)");
  cmd.add_option("--set-width", p.setnet.width, "Set network (--classifier setnet): width of each keypoint pair's embedding")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd.add_option("--set-epochs", p.setnet.epochs, "Set network: training epochs (Adam)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd.add_option("--set-min-steps", p.setnet.min_steps,
                 "Set network: at least this many mini-batches in all, however few the views (more epochs)")
      ->check(CLI::Range(0, 10000000))
      ->capture_default_str();
  cmd.add_option("--set-keypoint-dropout", p.setnet.keypoint_dropout,
                 "Set network training: each keypoint left out of a mini-batch with this probability")
      ->check(CLI::Range(0.0, 0.9))
      ->capture_default_str();
  cmd.add_option("--set-jitter", p.setnet.jitter_m,
                 "Set network training: each keypoint moved by Gaussian noise of this sigma (metres)")
      ->check(CLI::Range(0.0, 0.1))
      ->capture_default_str();
}

void addOpenSetOptions(CLI::App& cmd, learning::OpenSetOptions& o, std::string* method) {
  if (method)
    cmd.add_option("--open-set", *method,
                   "Open-set answers: none (closed-set: every view gets a class), knn (distance to the chosen class's "
                   "nearest training views), knn-relative (that distance over the class's own spread), max-probability, "
                   "or auto (" + std::string(learning::defaultOpenSetMethod()) +
                   " when the data has at least 3 categories, else closed-set)")
        ->capture_default_str();
  if (method)
    cmd.add_option("--open-set-scale", o.scale_by,
                   "knn-relative: camera (the distance over the class's scale times the view's camera's factor, "
                   "each camera told by its organized grid) or pooled (the class's scale alone, whatever the camera)")
        ->check(CLI::IsMember(learning::openSetScales()))
        ->capture_default_str();
  if (method)
    cmd.add_option("--open-set-class-scale", o.class_scale_power,
                   "knn-relative: each class's scale drawn toward the median class's, its own to this power times "
                   "the median's to 1 minus it (1: each class's own spread; 0: one scale for all)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
  cmd.add_option("--open-set-spread", o.class_spread,
                 "knn-relative: a class's scale from its views' spread (views: the nearest other view of it) or its "
                 "instances' (instances: the nearest view of another of its instances, for category models)")
      ->check(CLI::IsMember(learning::openSetSpreads()))
      ->capture_default_str();
  cmd.add_option("--open-set-distance", o.distance,
                 "knn, knn-relative: the distance to the nearest training views: rms (of the features standardised "
                 "by the training views' spread), or between the PDFs as described: l1 (the mass that moves) or chi2 "
                 "(the mass that moves, relative to the mass there)")
      ->check(CLI::IsMember(learning::openSetDistances()))
      ->capture_default_str();
  cmd.add_option("--false-accept", o.false_accept,
                 "Open-set: the rate of unknown views given a class that the threshold is calibrated for")
      ->check(CLI::Range(0.0, 0.99))
      ->capture_default_str();
  cmd.add_option("--open-set-groups", o.groups,
                 "Open-set: groups of categories left out in turn to calibrate the threshold (trainings)")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  cmd.add_option("--open-set-rule", o.rule,
                 "Open-set: the stated rate met on all the left-out views together (pooled) or on each left-out "
                 "group's alone (per-group: stricter; with --open-set-groups 1000, on every category)")
      ->check(CLI::IsMember(learning::openSetRules()))
      ->capture_default_str();
}

std::string openSetSummary(const learning::OpenSet& os) {
  if (!os.enabled()) return "";
  std::ostringstream out;
  out << std::fixed << "; open-set " << os.method << " threshold " << std::setprecision(4) << os.threshold << " for "
      << std::setprecision(1) << 100 * os.false_accept << " % false accepts (" << os.calibration_views
      << " views of left-out categories, " << os.calibration_groups << " trainings"
      << (os.rule == "per-group" ? ", met by each left-out group" : "") << ")";
  if (learning::keepsReferences(os.method) && os.distance != "rms") out << "; distance " << os.distance;
  for (const auto& [camera, f] : os.camera_scale) out << "; camera " << camera << " × " << std::setprecision(3) << f;
  if (os.class_scale_power != 1)
    out << "; class scales drawn toward their median (power " << std::setprecision(2) << os.class_scale_power << ")";
  if (std::isfinite(os.turn_threshold))
    out << ", a turn's " << std::setprecision(4) << os.turn_threshold << " (" << os.calibration_turns << " turns of "
        << learning::kTurnViews << " views)";
  return out.str();
}

void setOpenSetFlag(learning::OpenSetOptions& o, const std::string& method) {
  try {
    learning::setOpenSetMethod(o, method);
  } catch (const Error& e) {
    throw Error(std::string("--open-set: ") + e.what());
  }
}

std::vector<std::string> splitList(const std::string& list) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : list + " ") {
    if (c == ' ' || c == ',' || c == '\t' || c == '\n') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  return out;
}

}  // namespace keyturn::app
