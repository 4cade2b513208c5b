// keyturn evaluate --protocol fusion's report: JSON, a Markdown table per protocol (accuracy
// against the number of views, per schedule and method, true and shuffled poses), CSV, and one
// plot per protocol (accuracy against views beside single-view accuracy).
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "keyturn/learning/fusion_evaluation.h"
#include "report_numbers.h"

namespace keyturn::learning {
namespace {

using detail::formatNumber;
using detail::jsonNumber;
using detail::percent;

double singleView(const FusionProtocolResult& r) {
  return r.test_views ? static_cast<double>(r.single_view_correct) / static_cast<double>(r.test_views) : std::nan("");
}

}  // namespace

FusionReport fusionReport(const std::vector<FusionProtocolResult>& results, const std::string& dataset,
                          const std::string& features, const std::string& classifier,
                          const FusionEvaluationOptions& o) {
  FusionReport rep;
  nlohmann::json j = {{"dataset", dataset},          {"features", features},
                      {"classifier", classifier},    {"stop_belief", o.fusion.stop_belief},
                      {"bin_deg", o.fusion.bin_deg}, {"probability_floor", o.fusion.probability_floor},
                      {"max_views", o.max_views},    {"protocols", nlohmann::json::array()}};
  std::string md = "# Multi-view fusion: " + dataset + "\n\n" + features + ", " + classifier +
                   "; accuracy (%) of the fused answer after n views, pooled over the folds' sequences (one starting "
                   "at every held-out view); \"shuffled\": the same views with their poses dealt out in another "
                   "order. Stopping: views taken (up to " + std::to_string(o.max_views) + ", first schedule) until "
                   "the highest belief reaches " + formatNumber("%g", o.fusion.stop_belief) + ".\n";
  rep.csv = "protocol,schedule,method,poses,views,sequences,accuracy,mean_true_belief\n";
  for (const auto& r : results) {
    nlohmann::json pj = {{"protocol", r.protocol},       {"label", r.label_kind},
                         {"folds", r.folds},             {"test_views", r.test_views},
                         {"single_view_accuracy", jsonNumber(singleView(r))},
                         {"curves", nlohmann::json::array()}, {"stopping", nlohmann::json::array()}};
    md += "\n## " + r.protocol + " (" + r.label_kind + " labels, " + std::to_string(r.folds) + " folds, " +
          std::to_string(r.test_views) + " test views; single view " + percent(singleView(r)) + " %)\n\n";
    md += "| schedule | method | poses |";
    std::string rule = "|---|---|---|";
    for (int n = 1; n <= o.max_views; ++n) md += " " + std::to_string(n) + " |", rule += "---|";
    md += " belief in truth, " + std::to_string(o.max_views) + " views |\n" + rule + "---|\n";
    CurvePlot plot;
    plot.file = "accuracy_" + fileSafeName(r.protocol) + ".png";
    const std::string first = r.curves.empty() ? std::string() : r.curves.front().schedule;
    plot.title = "Fused accuracy against views " + first + ", " + r.protocol + " (" + features + ", " + classifier + ")";
    plot.x_label = "views";
    for (int n = 1; n <= o.max_views; ++n) plot.x_categories.push_back(std::to_string(n));
    plot.y_label = "accuracy (%)";
    for (const auto& c : r.curves) {
      nlohmann::json cj = {{"schedule", c.schedule}, {"method", c.method}, {"poses", c.shuffled ? "shuffled" : "true"},
                           {"views", nlohmann::json::array()}};
      md += "| " + c.schedule + " | " + c.method + " | " + (c.shuffled ? "shuffled" : "true") + " |";
      CurveSeries series{c.method + (c.shuffled ? ", shuffled poses" : ""), {}, {}};
      for (std::size_t n = 1; n <= c.sequences.size(); ++n) {
        cj["views"].push_back({{"n", n}, {"sequences", c.sequences[n - 1]}, {"accuracy", jsonNumber(c.accuracy(n))},
                               {"mean_true_belief", jsonNumber(c.meanTrueBelief(n))}});
        md += " " + percent(c.accuracy(n)) + " |";
        rep.csv += r.protocol + "," + c.schedule + "," + c.method + "," + (c.shuffled ? "shuffled" : "true") + "," +
                   std::to_string(n) + "," + std::to_string(c.sequences[n - 1]) + "," +
                   formatNumber("%.6f", c.accuracy(n)) + "," + formatNumber("%.6f", c.meanTrueBelief(n)) + "\n";
        if (std::isfinite(c.accuracy(n))) series.x.push_back(static_cast<double>(n - 1)), series.y.push_back(100 * c.accuracy(n));
      }
      const double belief = c.meanTrueBelief(c.sequences.size());
      md += " " + (std::isfinite(belief) ? formatNumber("%.3f", belief) : std::string("–")) + " |\n";
      // The first schedule's methods, and the shuffled control of those that use the poses (the
      // other schedules are in the table: a plot of them all has too many lines to read).
      if (c.schedule == first && (!c.shuffled || c.method != "independent"))
        plot.series.push_back(std::move(series));
      pj["curves"].push_back(std::move(cj));
    }
    plot.series.push_back(detail::singleViewSeries(o.max_views, singleView(r)));
    rep.plots.curves.push_back(std::move(plot));
    md += "\n![accuracy against views, " + r.protocol + "](" + rep.plots.curves.back().file + ")\n\n";
    md += "| stopping, " + (o.schedules.empty() ? std::string() : o.schedules.front().name) +
          " | sequences | accuracy % | mean views |\n|---|---|---|---|\n";
    for (const auto& s : r.stopping) {
      const double acc = s.sequences ? static_cast<double>(s.correct) / static_cast<double>(s.sequences) : std::nan("");
      const double views = s.sequences ? static_cast<double>(s.views) / static_cast<double>(s.sequences) : std::nan("");
      md += "| " + s.method + " | " + std::to_string(s.sequences) + " | " + percent(acc) + " | " +
            formatNumber("%.2f", views) + " |\n";
      pj["stopping"].push_back({{"method", s.method}, {"sequences", s.sequences}, {"accuracy", jsonNumber(acc)},
                                {"mean_views", jsonNumber(views)}});
    }
    j["protocols"].push_back(std::move(pj));
  }
  rep.json = j.dump(2) + "\n";
  rep.markdown = md;
  return rep;
}

}  // namespace keyturn::learning
