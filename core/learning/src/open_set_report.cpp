#include "open_set_report.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "keyturn/learning/open_set_evaluation.h"

namespace keyturn::learning {
namespace {

bool openSetRow(const EvaluationRow& r) {
  for (const auto& f : r.proto->folds)
    if (!f.unknown.empty()) return true;
  return false;
}

std::string pct(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << 100.0 * v;
  return s.str();
}

// At most ~200 points of a ROC curve: a plot does not need every distinct score.
CurveSeries rocSeries(const std::string& name, const OpenSetSummary& s) {
  const RocCurve c = rocCurve(s.known_scores, s.unknown_scores);
  CurveSeries out{name, {}, {}};
  const std::size_t step = std::max<std::size_t>(1, c.false_accept.size() / 200);
  for (std::size_t i = 0; i < c.false_accept.size(); i += step)
    out.x.push_back(100.0 * c.false_accept[i]), out.y.push_back(100.0 * c.true_accept[i]);
  out.x.push_back(100.0 * c.false_accept.back()), out.y.push_back(100.0 * c.true_accept.back());
  return out;
}

}  // namespace

nlohmann::json openSetRowJson(const EvaluationRun& run, const EvaluationRow& r) {
  if (!openSetRow(r)) return nullptr;
  nlohmann::json methods = nlohmann::json::array();
  for (const auto& s : summariseOpenSet(r.ev.folds)) {
    const auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    const nlohmann::json fused{{"views", kOpenSetFusedViews},
                               {"spread_deg", kOpenSetFusedSpreadDeg},
                               {"known_sequences", s.fused_known},
                               {"unknown_sequences", s.fused_unknown},
                               {"false_accept", number(s.fused_false_accept)},
                               {"known_accuracy_open", number(s.fused_known_accuracy_open)},
                               {"known_accuracy_closed", number(s.fused_known_accuracy_closed)}};
    methods.push_back({{"method", s.method},
                       {"auroc_mean", s.auroc_mean},
                       {"auroc_std", s.auroc_sd},
                       {"false_accept", s.false_accept},
                       {"false_accept_by_fold", [&] {
                          nlohmann::json by = nlohmann::json::array();
                          for (double v : s.false_accept_by_fold) by.push_back(number(v));
                          return by;
                        }()},
                       {"known_accuracy_open", s.known_accuracy_open},
                       {"known_accuracy_closed", s.known_accuracy_closed},
                       {"known_rejected", s.known_rejected},
                       {"known_views", s.known_views},
                       {"unknown_views", s.unknown_views},
                       {"fused", fused}});
  }
  return {{"false_accept_stated", run.plan.open_set.false_accept}, {"methods", methods}};
}

std::string openSetMarkdown(const EvaluationRun& run, ReportPlots& plots) {
  std::ostringstream md;
  for (const auto& pn : run.plan.protocols)
    for (int bins : run.plan.bins) {
      std::vector<const EvaluationRow*> rows;
      for (const auto& r : run.rows)
        if (r.protocol == pn && r.bins == bins && openSetRow(r)) rows.push_back(&r);
      if (rows.empty()) continue;
      const Protocol& p = *rows.front()->proto;
      md << "## Open-set answers: " << pn << ", " << bins << " bins\n\n"
         << p.folds.size() << " folds, each leaving one group of categories out of training (its views are the "
         << "unknowns) and testing the known categories' held-out views (" << p.labels.kindName()
         << " labels). Each method's threshold was calibrated on the fold's training views alone for a false-accept "
            "rate of "
         << pct(run.plan.open_set.false_accept) << " % (its categories dealt into at most "
         << run.plan.open_set.groups << " groups, each left out of one training; the rate met "
         << (run.plan.open_set.rule == "per-group" ? "by each left-out group's views alone" : "by their views pooled")
         << "). AUROC: known against unknown views, mean ± sd over folds; "
            "false accepts: unknown views given a class; known accuracy: known views accepted with their true class, "
            "against closed-set (every view given a class).\n\n"
         << "| features | classifier | method | AUROC | false accepts % | known accuracy % (open) | closed-set % | "
            "known rejected % |\n|---|---|---|---|---|---|---|---|\n";
      std::vector<std::string> files;
      std::ostringstream fused;  // the turns' table, when the views had angles
      std::ostringstream by_fold;  // the false accepts fold by fold: which categories are unknown decides them
      for (const auto& c : run.plan.classifiers)
        for (const EvaluationRow* r : rows) {
          if (r->classifier != c) continue;
          CurvePlot chart;  // one per classifier and feature set: the methods side by side
          chart.file = "roc/" + fileSafeName(pn + "_" + std::to_string(bins) + "bins_" + c + "_" + r->features) + ".png";
          chart.title = "Known vs unknown views: " + r->features + ", " + c + ", " + pn;
          chart.x_label = "unknown views accepted %";
          chart.y_label = "known views accepted %";
          chart.y_min = 0, chart.y_max = 100;
          std::string set;
          for (char ch : r->features) set += ch == '|' ? std::string("\\|") : std::string(1, ch);
          for (const auto& s : summariseOpenSet(r->ev.folds)) {
            md << "| " << set << " | " << c << " | " << s.method << " | " << std::fixed << std::setprecision(3)
               << s.auroc_mean << " ± " << s.auroc_sd << " | " << pct(s.false_accept) << " | "
               << pct(s.known_accuracy_open) << " | " << pct(s.known_accuracy_closed) << " | " << pct(s.known_rejected)
               << " |\n";
            chart.series.push_back(rocSeries(s.method, s));
            by_fold << "| " << set << " | " << c << " | " << s.method << " |";
            for (double v : s.false_accept_by_fold) by_fold << ' ' << (std::isfinite(v) ? pct(v) : "–") << " |";
            by_fold << '\n';
            if (s.fused_known && s.fused_unknown)
              fused << "| " << set << " | " << c << " | " << s.method << " | " << pct(s.known_accuracy_open) << " → "
                    << pct(s.fused_known_accuracy_open) << " | " << pct(s.known_accuracy_closed) << " → "
                    << pct(s.fused_known_accuracy_closed) << " | " << pct(s.false_accept) << " → "
                    << pct(s.fused_false_accept) << " | " << s.fused_known << " / " << s.fused_unknown << " |\n";
          }
          files.push_back(chart.file);
          plots.curves.push_back(chart);
        }
      md << "\nROC curves (all folds pooled, one per classifier and feature set):";
      for (const auto& f : files) md << " [" << f.substr(4, f.size() - 8) << "](" << f << ")";
      md << "\n\n### False accepts by fold\n\nThe unknown views given a class, % of each fold's: how near its "
            "unknown categories lie to the known ones decides it, not the calibration alone.\n\n"
         << "| features | classifier | method |";
      for (const auto& f : p.folds) md << ' ' << f.name << " |";
      md << "\n|---|---|---|";
      for (std::size_t k = 0; k < p.folds.size(); ++k) md << "---|";
      md << '\n' << by_fold.str() << '\n';
      if (!fused.str().empty())
        md << "### Over a turn of the table\n\nThe same views read as one object turning: " << kOpenSetFusedViews
           << " views spread over " << std::defaultfloat << kOpenSetFusedSpreadDeg
           << "°, starting at every view of a held-out capture group (instance and elevation), fused by pose; a view "
              "the method rejects adds no evidence and the answer is unknown while the views' mean score is under the turn threshold, "
              "calibrated as a view's is, for the stated rate, on turns of the training categories left out in turn "
              "(turn_fusion.h: the rule of the studio's live recognition and of a model's fused sequences). "
              "Single view → fused.\n\n"
           << "| features | classifier | method | known accuracy % (open) | closed-set % | false accepts % | "
              "sequences known / unknown |\n|---|---|---|---|---|---|---|\n"
           << fused.str() << "\n";
    }
  return md.str();
}

}  // namespace keyturn::learning
