#include "keyturn/learning/evaluation_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "keyturn/core/error.h"
#include "keyturn/core/parallel_for.h"
#include "keyturn/learning/open_set_evaluation.h"
#include "open_set_report.h"

namespace keyturn::learning {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string pct(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << 100.0 * v;
  return s.str();
}

ClassifierParams paramsOf(const EvaluationPlan& plan, const std::string& classifier) {
  ClassifierParams p = plan.params;
  p.kind = classifier;
  return p;
}

// "category for kfold4 and leave-instance" / "instance for kfold4, category for leave-instance":
// what each protocol's rows were judged by, as the report states it.
std::string labelsInWords(const EvaluationRun& run) {
  std::vector<std::pair<std::string, std::vector<std::string>>> by_kind;  // kind → protocols, first seen first
  for (const auto& pn : run.plan.protocols)
    for (const auto& p : run.protocols)
      if (p->name == pn) {
        const std::string kind = p->labels.kindName();
        auto it = std::find_if(by_kind.begin(), by_kind.end(), [&](const auto& e) { return e.first == kind; });
        if (it == by_kind.end()) by_kind.push_back({kind, {pn}});
        else if (std::find(it->second.begin(), it->second.end(), pn) == it->second.end()) it->second.push_back(pn);
        break;
      }
  std::string out;
  for (std::size_t k = 0; k < by_kind.size(); ++k) {
    out += (k ? ", " : "") + by_kind[k].first + " for ";
    const auto& names = by_kind[k].second;
    for (std::size_t i = 0; i < names.size(); ++i) out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  }
  if (run.plan.label)
    out += std::string(" (as asked: ") + (*run.plan.label == LabelKind::Category ? "category" : "instance") +
           (*run.plan.label == LabelKind::Instance && std::count(run.plan.protocols.begin(), run.plan.protocols.end(),
                                                                  std::string("leave-instance"))
                ? "; leave-instance is always judged by category"
                : "") +
           ")";
  return out;
}

// Mean ± 1 sd of a block's PDF over each class's views, one plot per class.
void addClassPdfPlots(const FeatureTable& t, const Labels& labels, const std::string& block, ReportPlots& plots) {
  for (const auto& c : classPdfs(t, labels, block)) {
    CurvePlot chart;
    chart.file = "pdfs/" + fileSafeName(block + "_" + c.label) + ".png";
    chart.title = block + " of " + c.label + " (" + std::to_string(c.views) + " views): mean ± 1 sd";
    chart.x_label = "bin";
    chart.y_label = "probability";
    CurveSeries mean{"mean", {}, {}}, hi{"+1 sd", {}, {}}, lo{"-1 sd", {}, {}};
    for (std::size_t b = 0; b < c.mean.size(); ++b) {
      for (auto* s : {&mean, &hi, &lo}) s->x.push_back(static_cast<double>(b));
      mean.y.push_back(c.mean[b]);
      hi.y.push_back(c.mean[b] + c.sd[b]);
      lo.y.push_back(std::max(0.0, c.mean[b] - c.sd[b]));
    }
    chart.series = {mean, hi, lo};
    chart.y_min = 0;
    chart.width = 640;
    chart.height = 400;
    plots.curves.push_back(chart);
  }
}

// A feature set as a Markdown table cell: a choice's '|' would end the cell.
std::string markdownCell(const std::string& set) {
  std::string out;
  for (char c : set) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// What nested validation chose in each row with a choice: "kpd2+kpa3 in 7 folds, s_kpd2+kpa3 in 3".
std::string nestedChoicesInWords(const EvaluationRun& run) {
  std::ostringstream md;
  for (const auto& r : run.rows) {
    if (featureSetChoices(r.features).size() < 2) continue;
    if (md.tellp() == 0)
      md << "## Choices made by nested validation\n\nPer fold, on at most " << run.plan.inner_folds
         << " inner folds of its training views (the protocol's other folds); the test views took no part.\n\n";
    std::vector<std::pair<std::string, int>> counts;
    for (const auto& f : r.ev.folds) {
      auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == f.chosen; });
      if (it == counts.end()) counts.push_back({f.chosen, 1});
      else ++it->second;
    }
    md << "- " << r.bins << " bins, " << r.protocol << ", " << r.classifier << ", `" << r.features << "`: ";
    for (std::size_t k = 0; k < counts.size(); ++k)
      md << (k ? ", " : "") << "`" << counts[k].first << "` in " << counts[k].second
         << (counts[k].second == 1 ? " fold" : " folds");
    md << "\n";
  }
  if (md.tellp() > 0) md << "\n";
  return md.str();
}

// The dataset's own views of a bin count's table, the twins appended for training left out: the
// table itself without augmentation, else a copy cut to them in `cut`.
const FeatureTable& datasetRows(const EvaluationRun& run, int bins, FeatureTable& cut) {
  const FeatureTable& t = run.tables.at(bins);
  const std::size_t originals = run.twins.at(bins).size();
  if (originals == 0) return t;
  cut = t;
  cut.rows.resize(originals);
  return cut;
}

// "Training augmented by DATASET (N views): …" — what the twins are and the rule they follow.
std::string augmentationInWords(const EvaluationRun& run, int bins) {
  const TwinRows& twins = run.twins.at(bins);
  if (twins.empty()) return "";
  std::size_t n = 0;
  for (const auto& t : twins) n += t.size();
  std::ostringstream md;
  md << "Training augmented by " << n << " twin views from";
  for (std::size_t k = 0; k < run.plan.train_extra.size(); ++k) md << (k ? ", " : " ") << "`" << run.plan.train_extra[k] << "`";
  md << ": a twin (the same view id rendered again) is trained on only in the folds, outer and inner, that train on "
        "its view; no test view and no twin of one was trained on.\n\n";
  return md.str();
}

}  // namespace

std::size_t EvaluationRun::totalFolds() const {
  std::size_t n = 0;
  for (const auto& r : rows) n += r.proto->folds.size();
  return n;
}

EvaluationRun prepareEvaluation(const EvaluationPlan& plan, const std::function<FeatureTable(int bins)>& describe,
                                const std::function<FeatureTable(const std::string&, int)>& describe_extra) {
  const auto start = Clock::now();
  if (plan.feature_sets.empty() || plan.classifiers.empty() || plan.protocols.empty() || plan.bins.empty())
    throw Error("evaluate needs at least one feature set, classifier and protocol");
  if (!plan.train_extra.empty() && !describe_extra) throw Error("evaluate: no way to describe the extra training datasets");
  for (const auto& c : plan.classifiers) makeClassifier(paramsOf(plan, c));  // unknown names fail before any work
  EvaluationRun run;
  run.plan = plan;
  for (int bins : plan.bins) {
    const auto t0 = Clock::now();
    run.tables[bins] = describe(bins);
    run.describe_s[bins] = secondsSince(t0);
    const FeatureTable& t = run.tables[bins];
    for (const auto& set : plan.feature_sets)
      for (const auto& choice : featureSetChoices(set))
        for (const auto& b : featureSetBlocks(choice))
          if (t.offset(b) < 0) throw Error("feature set '" + set + "': unknown block '" + b + "'");
    const std::size_t first = run.protocols.size();  // this bin count's, made before any twin joins
    for (const auto& pn : plan.protocols)
      run.protocols.push_back(std::make_unique<Protocol>(makeProtocol(pn, t, plan.split_seed, plan.label)));
    for (std::size_t k = first; k < run.protocols.size(); ++k)  // refused before any twin is described
      for (const auto& set : plan.feature_sets)
        if (featureSetChoices(set).size() > 1 && run.protocols[k]->folds.size() < 2)
          throw Error("feature set '" + set + "': a choice needs a protocol of at least two folds (" +
                      run.protocols[k]->name + " has " + std::to_string(run.protocols[k]->folds.size()) + ")");
    TwinRows& twins = run.twins[bins];
    for (const auto& extra : plan.train_extra) {
      const TwinRows more = appendTwins(run.tables[bins], describe_extra(extra, bins), extra);
      if (twins.empty()) twins.resize(more.size());
      for (std::size_t r = 0; r < more.size(); ++r) twins[r].insert(twins[r].end(), more[r].begin(), more[r].end());
    }
    if (!plan.train_extra.empty()) run.describe_s[bins] = secondsSince(t0);
    for (std::size_t k = first; k < run.protocols.size(); ++k) {
      Protocol& p = *run.protocols[k];
      p.labels.of_row = labelsWithTwins(std::move(p.labels.of_row), twins);
      for (const auto& set : plan.feature_sets)
        for (const auto& c : plan.classifiers) run.rows.push_back({bins, p.name, set, c, &p, {}});
    }
  }
  run.total_s = secondsSince(start);
  return run;
}

std::vector<FoldJob> foldJobs(const EvaluationRun& run, int shard, int shards) {
  if (shards < 1 || shard < 0 || shard >= shards)
    throw Error("shard " + std::to_string(shard + 1) + " of " + std::to_string(shards) +
                ": expected 1 <= shard <= shards");
  std::vector<FoldJob> jobs;
  std::size_t j = 0;
  for (std::size_t r = 0; r < run.rows.size(); ++r)
    for (std::size_t f = 0; f < run.rows[r].proto->folds.size(); ++f, ++j)
      if (static_cast<int>(j % static_cast<std::size_t>(shards)) == shard) jobs.push_back({r, f});
  return jobs;
}

void evaluateRows(EvaluationRun& run, const std::function<void()>& fold_done, int shard, int shards) {
  const auto start = Clock::now();
  const std::vector<FoldJob> jobs = foldJobs(run, shard, shards);
  for (auto& r : run.rows) r.ev.folds.assign(r.proto->folds.size(), {});
  const auto& tables = run.tables;
  std::map<int, std::vector<double>> azimuths;  // per bin count, one per table row (twins: NaN)
  if (!run.plan.azimuth_deg.empty())
    for (const auto& [bins, table] : tables)
      for (const auto& row : table.rows) {
        const auto it = run.plan.azimuth_deg.find(row.id);
        azimuths[bins].push_back(it == run.plan.azimuth_deg.end() ? std::nan("") : it->second);
      }
  std::mutex mutex;
  // All the shard's folds in one pool, across rows: no row's last fold holds up the next row.
  parallelFor(jobs.size(), run.plan.jobs, [&](std::size_t i) {
    EvaluationRow& r = run.rows[jobs[i].row];
    ClassifierParams params = paramsOf(run.plan, r.classifier);
    params.xgboost.threads = 1;  // parallel over folds instead
    const std::vector<std::string> choices = featureSetChoices(r.features);
    const int classes = static_cast<int>(r.proto->labels.names.size());
    const Fold& fold = r.proto->folds[jobs[i].fold];
    if (!fold.unknown.empty()) {  // open-set: the choice (if any) on inner closed-set folds, as below
      std::vector<double> inner;
      const std::size_t pick = choices.size() > 1 ? chooseFeatureSet(tables.at(r.bins), choices, r.proto->labels.of_row,
                                                                     classes, r.proto->folds, jobs[i].fold,
                                                                     run.plan.inner_folds, params, run.twins.at(r.bins), inner)
                                                  : 0;
      FoldOutcome o = evaluateOpenSetFold(tables.at(r.bins), featureSetBlocks(choices[pick]), r.proto->labels.of_row,
                                          fold, params, run.plan.open_set, run.twins.at(r.bins),
                                          azimuths.count(r.bins) ? azimuths.at(r.bins) : std::vector<double>{});
      if (choices.size() > 1) o.chosen = choices[pick], o.inner_accuracy = std::move(inner);
      r.ev.folds[jobs[i].fold] = std::move(o);
    } else {
      r.ev.folds[jobs[i].fold] =
          choices.size() > 1
              ? evaluateFoldChoosing(tables.at(r.bins), choices, r.proto->labels.of_row, classes, r.proto->folds,
                                     jobs[i].fold, run.plan.inner_folds, params, run.twins.at(r.bins))
              : evaluateFold(tables.at(r.bins), featureSetBlocks(r.features), r.proto->labels.of_row, classes, fold,
                             params, run.twins.at(r.bins));
    }
    std::lock_guard<std::mutex> lock(mutex);
    if (fold_done) fold_done();
  });
  for (auto& r : run.rows) r.ev.confusion = sumConfusion(r.ev.folds, static_cast<int>(r.proto->labels.names.size()));
  run.total_s += secondsSince(start);
}

EvaluationReport evaluationReport(const EvaluationRun& run) {
  const EvaluationPlan& a = run.plan;
  const auto& rows = run.rows;
  EvaluationReport report;

  // CSV and JSON: every row.
  std::ostringstream csv;
  csv << "bins,protocol,label,features,classifier,folds,test_views,accuracy_mean,accuracy_std,"
         "train_ms_per_view,predict_ms_per_view\n";
  nlohmann::json js;
  js["dataset"] = a.dataset;
  js["seconds"] = run.total_s;
  if (!a.train_extra.empty()) js["train_extra"] = a.train_extra;
  for (const auto& r : rows) {
    std::size_t tested = 0;
    nlohmann::json folds = nlohmann::json::array();
    for (const auto& f : r.ev.folds) {
      tested += f.test_views;
      folds.push_back({{"name", f.name}, {"accuracy", f.accuracy()}, {"train_views", f.train_views},
                       {"test_views", f.test_views}});
      if (f.twin_views) folds.back()["twin_views"] = f.twin_views;
      if (!f.chosen.empty()) folds.back()["chosen"] = f.chosen, folds.back()["inner_accuracy"] = f.inner_accuracy;
    }
    csv << r.bins << ',' << r.protocol << ',' << r.proto->labels.kindName() << ',' << r.features << ',' << r.classifier
        << ',' << r.ev.folds.size() << ',' << tested << ',' << r.ev.mean() << ',' << r.ev.stddev() << ','
        << r.ev.trainMsPerView() << ',' << r.ev.predictMsPerView() << '\n';
    js["rows"].push_back({{"bins", r.bins}, {"protocol", r.protocol}, {"label", r.proto->labels.kindName()},
                          {"features", r.features}, {"classifier", r.classifier}, {"accuracy_mean", r.ev.mean()},
                          {"accuracy_std", r.ev.stddev()}, {"train_ms_per_view", r.ev.trainMsPerView()},
                          {"predict_ms_per_view", r.ev.predictMsPerView()}, {"folds", folds}});
    if (const nlohmann::json open = openSetRowJson(run, r); !open.is_null()) js["rows"].back()["open_set"] = open;
  }
  report.csv = csv.str();
  report.json = js.dump(2) + "\n";

  // Markdown: one Table-2-style table per bin count.
  std::ostringstream md;
  md << "# keyturn evaluate: " << a.dataset << "\n\n";
  for (int bins : a.bins) {
    FeatureTable cut;
    const TableSummary s = summarise(datasetRows(run, bins, cut), a.low_keypoints);
    const double describe_s = run.describe_s.at(bins);
    md << "## " << bins << " bins\n\n"
       << s.views << " views; ISS keypoints K per view: median " << s.k_median << " (" << s.k_min << "–" << s.k_max
       << "), " << s.low << " views with K < " << a.low_keypoints << ", " << s.failed
       << " views without keypoint features. Features described in " << std::fixed << std::setprecision(1)
       << describe_s << " s (" << std::setprecision(1) << 1000.0 * describe_s / std::max<std::size_t>(1, s.views)
       << " ms/view wall; 0 when cached).\n\n";
    std::vector<std::string> missing;
    for (const auto& [b, n] : s.missing)
      if (n) missing.push_back(b + " " + std::to_string(n));
    if (!missing.empty()) {
      md << "Views missing a block (kept in every protocol; XGBoost treats the values as missing, the network as 0): ";
      for (std::size_t i = 0; i < missing.size(); ++i) md << (i ? ", " : "") << missing[i];
      md << ".\n\n";
    }
    md << augmentationInWords(run, bins);
    md << "Accuracy % (mean ± sd over folds). Labels: " << labelsInWords(run) << ".\n\n| features |";
    for (const auto& pn : a.protocols)
      for (const auto& c : a.classifiers) md << ' ' << c << " " << pn << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < a.protocols.size() * a.classifiers.size(); ++i) md << "---|";
    md << "\n";
    for (const auto& set : a.feature_sets) {
      md << "| " << markdownCell(set) << " |";
      for (const auto& pn : a.protocols)
        for (const auto& c : a.classifiers)
          for (const auto& r : rows)
            if (r.bins == bins && r.protocol == pn && r.features == set && r.classifier == c)
              md << ' ' << pct(r.ev.mean()) << " ± " << pct(r.ev.stddev()) << " |";
      md << "\n";
    }
    md << "\n";
  }
  md << openSetMarkdown(run, report.plots);
  md << nestedChoicesInWords(run);
  md << "Train time per training view (mean over rows): ";
  for (const auto& c : a.classifiers) {
    double ms = 0;
    int n = 0;
    for (const auto& r : rows)
      if (r.classifier == c) ms += r.ev.trainMsPerView(), ++n;
    md << c << " " << std::setprecision(3) << ms / std::max(1, n) << " ms; ";
  }
  md << "\nTotal wall time " << std::setprecision(0) << run.total_s << " s.\n\n";

  // Confusion matrices of the best row per protocol (and bin count).
  md << "## Confusion matrices (best row per protocol)\n\n";
  for (const auto& pn : a.protocols)
    for (int bins : a.bins) {
      const EvaluationRow* best = nullptr;
      for (const auto& r : rows)
        if (r.protocol == pn && r.bins == bins && (!best || r.ev.mean() > best->ev.mean())) best = &r;
      if (!best) continue;
      const std::string file = "confusion/" + fileSafeName(pn + "_" + std::to_string(bins) + "bins") + ".png";
      report.plots.confusions.push_back(
          {file, pn + ": " + best->features + ", " + best->classifier + " (" + pct(best->ev.mean()) + "%)",
           best->proto->labels.names, best->ev.confusion});
      md << "- " << pn << ", " << bins << " bins: " << best->features << " with " << best->classifier << " → ["
         << file << "](" << file << ")\n";
    }

  // Per-class PDFs (instances) of the paper's main functions and a baseline.
  FeatureTable cut;
  const FeatureTable& t0 = datasetRows(run, a.bins.front(), cut);
  const Labels by_instance = labelRows(t0, LabelKind::Instance);
  for (const std::string block : {"kpd2", "gkpd2", "kpa3", "d2"}) addClassPdfPlots(t0, by_instance, block, report.plots);
  md << "\nPer-class PDFs (mean ± 1 sd over each instance's views): `pdfs/`.\n";

  // Bin-count sweep (the paper's Fig. 20).
  if (a.bins.size() > 1) {
    for (const auto& pn : a.protocols)
      for (const auto& c : a.classifiers) {
        CurvePlot chart;
        chart.file = "bins_" + fileSafeName(c + "_" + pn) + ".png";
        chart.title = "Accuracy vs bins, " + c + ", " + pn;
        chart.x_label = "bins";
        chart.y_label = "accuracy %";
        for (const auto& set : a.feature_sets) {
          CurveSeries s{set, {}, {}};
          for (const auto& r : rows)
            if (r.protocol == pn && r.classifier == c && r.features == set)
              s.x.push_back(r.bins), s.y.push_back(100.0 * r.ev.mean());
          chart.series.push_back(s);
        }
        report.plots.curves.push_back(chart);
        md << "- bin sweep " << c << ", " << pn << ": [" << chart.file << "](" << chart.file << ")\n";
      }
  }
  report.markdown = md.str();
  return report;
}

}  // namespace keyturn::learning
