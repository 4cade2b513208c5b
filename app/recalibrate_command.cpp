// keyturn recalibrate: a trained model's open-set answers calibrated anew from the training views it
// keeps — another false-accept rate, method, scale or distance, without its datasets. The classifier
// is kept as it is. The work is learning::recalibrateOpenSet's; this parses, calls and prints.
#include <cmath>
#include <iostream>
#include <memory>

#include "commands.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/model_recalibration.h"
#include "learning_options.h"

namespace keyturn::app {
namespace {

// Each option left out keeps the model's own setting: empty text, NaN or 0 mean "not given".
struct RecalibrateArgs {
  std::string model, out, method, scale_by, spread, distance, rule;
  double false_accept = std::nan(""), class_scale_power = std::nan("");
  int groups = 0;
  bool quiet = false;
};

int runRecalibrate(const RecalibrateArgs& a) {
  learning::Model m = learning::loadModel(a.model);
  if (!m.info.open_set.enabled())
    throw Error(a.model + ": a closed-set model has no open set to recalibrate (keyturn train --open-set)");
  learning::OpenSetOptions o = learning::openSetOptionsOf(m);
  if (!a.method.empty()) o.methods = {a.method};
  if (!a.scale_by.empty()) o.scale_by = a.scale_by;
  if (!a.spread.empty()) o.class_spread = a.spread;
  if (!a.distance.empty()) o.distance = a.distance;
  if (std::isfinite(a.false_accept)) o.false_accept = a.false_accept;
  if (std::isfinite(a.class_scale_power)) o.class_scale_power = a.class_scale_power;
  if (a.groups > 0) o.groups = a.groups;
  if (!a.rule.empty()) o.rule = a.rule;
  if (!a.quiet)
    std::cerr << "keyturn recalibrate: " << m.info.training_views.views.size() << " kept training views, "
              << o.groups << " trainings without a group of categories each…\n";
  const learning::OpenSet before = m.info.open_set;
  learning::recalibrateOpenSet(m, o, a.model);
  learning::saveModel(a.out, m);
  if (!a.quiet)
    std::cerr << "keyturn recalibrate: " << m.info.classes.size() << " classes, the classifier kept (threshold before "
              << before.threshold << ")" << openSetSummary(m.info.open_set) << " → " << a.out << "\n";
  return 0;
}

}  // namespace

Command addRecalibrateCommand(CLI::App& app) {
  auto a = std::make_shared<RecalibrateArgs>();
  auto* cmd = app.add_subcommand(
      "recalibrate",
      "Calibrate a trained model's open-set answers anew from the training views it keeps (the classifier is kept); "
      "each option left out keeps the model's own");
  cmd->add_option("model", a->model, "A model folder (keyturn train with an open set knn or knn-relative)")->required();
  cmd->add_option("--out,-o", a->out, "The recalibrated model's folder (may be the model's)")->required();
  cmd->add_option("--open-set", a->method, "Method: knn, knn-relative or max-probability")
      ->check(CLI::IsMember({"knn", "knn-relative", "max-probability"}));
  cmd->add_option("--open-set-distance", a->distance,
                  "knn, knn-relative: rms (of the standardised features) or, between the PDFs as described, l1 or chi2")
      ->check(CLI::IsMember(learning::openSetDistances()));
  cmd->add_option("--open-set-scale", a->scale_by, "knn-relative: camera or pooled")
      ->check(CLI::IsMember(learning::openSetScales()));
  cmd->add_option("--open-set-class-scale", a->class_scale_power,
                  "knn-relative: the power each class's scale is drawn toward the median class's by (1: its own)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--open-set-spread", a->spread, "knn-relative: views or instances")
      ->check(CLI::IsMember(learning::openSetSpreads()));
  cmd->add_option("--false-accept", a->false_accept,
                  "The rate of unknown views given a class that the threshold is calibrated for")
      ->check(CLI::Range(0.0, 0.99));
  cmd->add_option("--open-set-groups", a->groups, "Groups of categories left out in turn (trainings)")
      ->check(CLI::Range(2, 1000));
  cmd->add_option("--open-set-rule", a->rule,
                  "pooled (the stated rate on all left-out views together) or per-group (on each left-out group's)")
      ->check(CLI::IsMember(learning::openSetRules()));
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  return {cmd, [a] { return runRecalibrate(*a); }};
}

}  // namespace keyturn::app
