// keyturn evaluate --protocol nbv's report: JSON, a Markdown section per protocol (accuracy against
// the number of views, next best view beside the fixed steps; the stopping rule's sweep; the views
// next best view needs to reach the fixed steps' accuracy), CSV, and one plot per protocol.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "keyturn/learning/nbv_evaluation.h"
#include "report_numbers.h"

namespace keyturn::learning {
namespace {

using detail::formatNumber;
using detail::jsonNumber;
using detail::percent;

std::string views(double v) { return std::isfinite(v) ? formatNumber("%.2f", v) : "not reached"; }

double singleView(const NbvProtocolResult& r) {
  return r.test_views ? static_cast<double>(r.single_view_correct) / static_cast<double>(r.test_views) : std::nan("");
}

// The least n whose accuracy reaches `target` on a curve (NaN when none does).
double curveViewsToReach(const ViewCountCurve& c, double target) {
  for (std::size_t n = 1; n <= c.sequences.size(); ++n)
    if (c.accuracy(n) >= target - 1e-12) return static_cast<double>(n);
  return std::nan("");
}

}  // namespace

NbvReport nbvReport(const std::vector<NbvProtocolResult>& results, const std::string& dataset,
                    const std::string& features, const std::string& classifier, const NbvEvaluationOptions& o) {
  NbvReport rep;
  const std::string fixed = o.fixed.empty() ? std::string() : o.fixed.front().name;
  nlohmann::json j = {{"dataset", dataset},
                      {"features", features},
                      {"classifier", classifier},
                      {"method", "pose"},
                      {"bin_deg", o.fusion.bin_deg},
                      {"max_views", o.max_views},
                      {"target_views", o.target_views},
                      {"target_schedule", fixed},
                      {"candidate_step_deg", o.candidate_step_deg},
                      {"likelihood_window_deg", o.likelihood_window_deg},
                      {"start_every", o.start_every},
                      {"protocols", nlohmann::json::array()}};
  std::string md = "# Next best view: " + dataset + "\n\n" + features + ", " + classifier +
                   ", pose fusion. Accuracy (%) of the fused answer after n views, pooled over sequences starting at " +
                   (o.start_every > 1 ? "every " + std::to_string(o.start_every) + "th" : std::string("every")) +
                   " held-out view: *next best view* turns, after each view, to the reachable angle (every " +
                   formatNumber("%g", o.candidate_step_deg) + "° from the first view) with the lowest expected "
                   "entropy of the class belief, from per-angle confusions estimated on the training views; the "
                   "fixed schedules step by their angle. Target: " + fixed + " after " +
                   std::to_string(o.target_views) + " views. Stopping: views taken (up to " +
                   std::to_string(o.max_views) + ") until the highest belief reaches the threshold.\n";
  rep.csv = "protocol,policy,kind,views_or_threshold,sequences,accuracy,mean_views\n";
  for (const auto& r : results) {
    const double target = r.target();
    const double nbv_views = viewsToReach(r, kNextBestViewPolicy, target);
    const double fixed_views = viewsToReach(r, fixed, target);
    nlohmann::json pj = {{"protocol", r.protocol},
                         {"label", r.label_kind},
                         {"folds", r.folds},
                         {"test_views", r.test_views},
                         {"single_view_accuracy", jsonNumber(singleView(r))},
                         {"target_accuracy", jsonNumber(target)},
                         {"nbv_mean_views_to_target", jsonNumber(nbv_views)},
                         {"fixed_mean_views_to_target", jsonNumber(fixed_views)},
                         {"curves", nlohmann::json::array()},
                         {"stopping", nlohmann::json::array()},
                         {"first_turns", nlohmann::json::object()}};
    md += "\n## " + r.protocol + " (" + r.label_kind + " labels, " + std::to_string(r.folds) + " folds, " +
          std::to_string(r.test_views) + " test views; single view " + percent(singleView(r)) + " %)\n\n";
    md += "| policy |";
    std::string rule = "|---|";
    for (int n = 1; n <= o.max_views; ++n) md += " " + std::to_string(n) + " |", rule += "---|";
    md += " views to reach " + percent(target) + " % |\n" + rule + "---|\n";
    CurvePlot plot;
    plot.file = "nbv_" + fileSafeName(r.protocol) + ".png";
    plot.title = "Accuracy against number of views, " + r.protocol + " (" + features + ", " + classifier + ")";
    plot.x_label = "views";
    plot.y_label = "accuracy (%)";
    for (int n = 1; n <= o.max_views; ++n) plot.x_categories.push_back(std::to_string(n));
    for (const auto& c : r.curves) {
      nlohmann::json cj = {{"policy", c.policy}, {"views", nlohmann::json::array()}};
      md += "| " + c.policy + " |";
      CurveSeries series{c.policy, {}, {}};
      for (std::size_t n = 1; n <= c.sequences.size(); ++n) {
        cj["views"].push_back({{"n", n}, {"sequences", c.sequences[n - 1]}, {"accuracy", jsonNumber(c.accuracy(n))}});
        md += " " + percent(c.accuracy(n)) + " |";
        rep.csv += r.protocol + "," + c.policy + ",views," + std::to_string(n) + "," + std::to_string(c.sequences[n - 1]) +
                   "," + formatNumber("%.6f", c.accuracy(n)) + "," + std::to_string(n) + "\n";
        if (std::isfinite(c.accuracy(n))) series.x.push_back(static_cast<double>(n - 1)), series.y.push_back(100 * c.accuracy(n));
      }
      const double reach = curveViewsToReach(c, target);
      md += " " + (std::isfinite(reach) ? std::to_string(static_cast<int>(reach)) : std::string("not reached")) + " |\n";
      plot.series.push_back(std::move(series));
      pj["curves"].push_back(std::move(cj));
    }
    plot.series.push_back(detail::singleViewSeries(o.max_views, singleView(r)));
    rep.plots.curves.push_back(std::move(plot));
    md += "\n![accuracy against number of views, " + r.protocol + "](" + rep.plots.curves.back().file + ")\n\n";
    md += "Stopping rule (accuracy % @ mean views):\n\n| policy |";
    rule = "|---|";
    for (double b : o.stop_beliefs) md += " " + formatNumber("%g", b) + " |", rule += "---|";
    md += "\n" + rule + "\n";
    std::string policy;
    for (const auto& s : r.stopping) {
      if (s.policy != policy) {
        if (!policy.empty()) md += "\n";
        policy = s.policy;
        md += "| " + policy + " |";
      }
      md += " " + percent(s.accuracy()) + " @ " + formatNumber("%.2f", s.meanViews()) + " |";
      pj["stopping"].push_back({{"policy", s.policy}, {"stop_belief", s.stop_belief}, {"sequences", s.sequences},
                                {"accuracy", jsonNumber(s.accuracy())}, {"mean_views", jsonNumber(s.meanViews())}});
      rep.csv += r.protocol + "," + s.policy + ",stop," + formatNumber("%g", s.stop_belief) + "," +
                 std::to_string(s.sequences) + "," + formatNumber("%.6f", s.accuracy()) + "," +
                 formatNumber("%.6f", s.meanViews()) + "\n";
    }
    md += "\n\nThe target, " + fixed + " after " + std::to_string(o.target_views) + " views: " + percent(target) +
          " %. Under the stopping rule, next best view reaches it with " + views(nbv_views) + " views on average; " +
          fixed + " with " + views(fixed_views) + ".\n\nNext best view's first turn (degrees: sequences):";
    for (const auto& [turn, n] : r.first_turns) {
      md += " " + std::to_string(turn) + "°: " + std::to_string(n) + ",";
      pj["first_turns"][std::to_string(turn)] = n;
    }
    if (!r.first_turns.empty()) md.pop_back();
    md += "\n";
    j["protocols"].push_back(std::move(pj));
  }
  rep.json = j.dump(2) + "\n";
  rep.markdown = md;
  return rep;
}

}  // namespace keyturn::learning
