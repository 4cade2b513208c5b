#include "keyturn/learning/open_set_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "keyturn/core/error.h"
#include "keyturn/learning/splits.h"
#include "keyturn/learning/turn_fusion.h"
#include "fold_views.h"

namespace keyturn::learning {

std::vector<int> compactClasses(const std::vector<int>& y, std::vector<int>* present) {
  const std::set<int> distinct(y.begin(), y.end());
  std::map<int, int> index;
  for (int c : distinct) index.emplace(c, static_cast<int>(index.size()));
  if (present) present->assign(distinct.begin(), distinct.end());
  std::vector<int> out;
  out.reserve(y.size());
  for (int c : y) out.push_back(index.at(c));
  return out;
}

void setOpenSetMethod(OpenSetOptions& o, const std::string& method) {
  o.required = method != "auto";
  o.methods.clear();
  if (method == "none") return;
  const std::string m = method == "auto" ? defaultOpenSetMethod() : method;
  const auto& known = openSetMethods();
  if (std::find(known.begin(), known.end(), m) == known.end())
    throw Error("open-set method '" + method + "' is not one of auto, max-probability, knn, knn-relative, none");
  o.methods.push_back(m);
}

namespace {

Matrix rowsOf(const Matrix& x, const std::vector<std::size_t>& rows) {
  Matrix out(static_cast<Eigen::Index>(rows.size()), x.cols());
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = x.row(static_cast<Eigen::Index>(rows[i]));
  return out;
}

}  // namespace

std::vector<OpenSet> calibrateOpenSets(const Matrix& x, const std::vector<int>& y,
                                       const std::vector<std::string>& categories, const ClassifierParams& params,
                                       const OpenSetOptions& o, const TurnRows* turns,
                                       const std::vector<std::string>* cameras,
                                       const std::vector<std::string>* instances) {
  if (o.methods.empty()) return {};
  for (const auto& m : o.methods) checkOpenSetMethod(m);
  checkOpenSetScale(o.scale_by);
  checkOpenSetSpread(o.class_spread);
  checkOpenSetDistance(o.distance);
  checkOpenSetRule(o.rule);
  if (instances && instances->size() != y.size())
    throw Error("open-set calibration: " + std::to_string(y.size()) + " rows but " + std::to_string(instances->size()) +
                " instances");
  if (cameras && cameras->size() != y.size())
    throw Error("open-set calibration: " + std::to_string(y.size()) + " rows but " + std::to_string(cameras->size()) +
                " cameras");
  if (static_cast<std::size_t>(x.rows()) != y.size() || y.size() != categories.size())
    throw Error("open-set calibration: rows, labels and categories differ in number");
  if (turns && (turns->group.size() != y.size() || turns->azimuth_deg.size() != y.size()))
    throw Error("open-set calibration: " + std::to_string(y.size()) + " rows but " + std::to_string(turns->group.size()) +
                " capture groups and " + std::to_string(turns->azimuth_deg.size()) + " angles");
  const std::vector<std::string> distinct = [&] {
    const std::set<std::string> s(categories.begin(), categories.end());
    return std::vector<std::string>(s.begin(), s.end());
  }();
  if (distinct.size() < kOpenSetMinCategories)
    throw Error("open-set calibration leaves categories out of training: it needs at least 3 categories, the "
                "training views have " + std::to_string(distinct.size()));
  const std::vector<int> group_of = categoryGroups(distinct, o.groups, o.seed);
  const int groups = *std::max_element(group_of.begin(), group_of.end()) + 1;
  std::vector<std::vector<double>> unknown(o.methods.size()), unknown_turns(o.methods.size());
  // per-group: the strictest of the groups' own thresholds (-inf until a group has views or turns).
  const bool per_group = o.rule == "per-group";
  const double none = -std::numeric_limits<double>::infinity();
  std::vector<double> strictest(o.methods.size(), none), strictest_turn(o.methods.size(), none);
  for (int g = 0; g < groups; ++g) {
    std::vector<std::size_t> train, held;
    for (std::size_t r = 0; r < categories.size(); ++r) {
      const auto at = std::lower_bound(distinct.begin(), distinct.end(), categories[r]) - distinct.begin();
      (group_of[static_cast<std::size_t>(at)] == g ? held : train).push_back(r);
    }
    std::vector<int> ytrain;
    for (auto r : train) ytrain.push_back(y[r]);
    const std::vector<int> compact = compactClasses(ytrain);
    const int inner_classes = compact.empty() ? 0 : *std::max_element(compact.begin(), compact.end()) + 1;
    if (inner_classes < 2 || held.empty()) continue;  // nothing to learn or to score without this group
    const Matrix xtrain = rowsOf(x, train), xheld = rowsOf(x, held);
    std::vector<std::string> camtrain, camheld, insttrain;
    if (cameras) {
      for (auto r : train) camtrain.push_back((*cameras)[r]);
      for (auto r : held) camheld.push_back((*cameras)[r]);
    }
    if (instances)
      for (auto r : train) insttrain.push_back((*instances)[r]);
    auto clf = makeClassifier(params);
    clf->fit(xtrain, compact, inner_classes);
    const Matrix p = clf->predictProba(xheld);
    // The left-out views read as turns: the mean score of each turn's views (TurnFusion's rule).
    std::vector<std::vector<int>> held_turns;
    if (turns) {
      std::vector<double> az;
      std::vector<std::string> group;
      for (auto r : held) az.push_back(turns->azimuth_deg[r]), group.push_back(turns->group[r]);
      held_turns = turnsOf(az, group);
    }
    for (std::size_t m = 0; m < o.methods.size(); ++m) {
      const OpenSet scorer =
          fitOpenSetScorer(o.methods[m], xtrain, compact, o.neighbours, o.scale_by, cameras ? &camtrain : nullptr,
                           o.class_scale_power, o.class_spread, instances ? &insttrain : nullptr, o.distance);
      const std::vector<double> s = openSetScores(scorer, xheld, p, cameras ? &camheld : nullptr);
      unknown[m].insert(unknown[m].end(), s.begin(), s.end());
      if (per_group) strictest[m] = std::max(strictest[m], thresholdForFalseAccept(s, o.false_accept));
      std::vector<double> turn_scores;
      for (const auto& seq : held_turns) {
        double sum = 0;
        for (int i : seq) sum += std::isfinite(s[static_cast<std::size_t>(i)]) ? s[static_cast<std::size_t>(i)] : 0.0;
        turn_scores.push_back(sum / static_cast<double>(seq.size()));
      }
      if (per_group && !turn_scores.empty())
        strictest_turn[m] = std::max(strictest_turn[m], thresholdForFalseAccept(turn_scores, o.false_accept));
      unknown_turns[m].insert(unknown_turns[m].end(), turn_scores.begin(), turn_scores.end());
    }
  }
  std::vector<OpenSet> out;
  for (std::size_t m = 0; m < o.methods.size(); ++m) {
    OpenSet s = fitOpenSetScorer(o.methods[m], x, y, o.neighbours, o.scale_by, cameras, o.class_scale_power,
                                 o.class_spread, instances, o.distance);
    s.threshold = per_group && !unknown[m].empty() ? strictest[m] : thresholdForFalseAccept(unknown[m], o.false_accept);
    s.rule = o.rule;
    s.false_accept = o.false_accept;
    s.calibration_views = static_cast<int>(unknown[m].size());
    s.calibration_groups = groups;
    if (!unknown_turns[m].empty()) {
      s.turn_threshold = per_group ? strictest_turn[m] : thresholdForFalseAccept(unknown_turns[m], o.false_accept);
      s.calibration_turns = static_cast<int>(unknown_turns[m].size());
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace keyturn::learning
