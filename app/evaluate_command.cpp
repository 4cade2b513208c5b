// keyturn evaluate: the paper's Table 2 for a dataset — accuracy (mean ± spread
// over folds) per feature set, classifier and protocol, the peers on the same
// views and splits, with confusion matrices and per-class PDF plots.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "dataset_features.h"
#include "descriptor_options.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/evaluation.h"
#include "keyturn/learning/protocols.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/ui/confusion_plot.h"
#include "keyturn/ui/line_chart.h"
#include "learning_options.h"
#include "progress.h"

namespace keyturn::app {
namespace {

namespace fs = std::filesystem;
using learning::FeatureTable;

const char* kDefaultFeatures =
    "kpd2 kpd3 kpa3 gkpd2 gkpd1 gkpcd2 kpd2+kpa3 kpd2+gkpd2 kpd2+gkpcd2 kpd2+gkpd2+gkpcd2 "
    "kpa3+kpd2+gkpd2+gkpcd2 u_kpd2+u_gkpd2 u_kpa3+u_kpd2+u_gkpd2+u_gkpcd2 esf vfh ourcvfh d2 d3 a3";

struct EvaluateArgs {
  std::string dataset, features = kDefaultFeatures, classifiers = "xgboost,mlp",
                       protocols = "kfold10,leave-elevation,leave-instance", bins, out;
  bool json = false, quiet = false;
  int jobs = 0;
  std::uint64_t split_seed = 7;
  DescriptorFlags flags;
  learning::ClassifierParams params;
};

using learning::Protocol;

struct Row {
  int bins = 0;
  std::string protocol, features, classifier;
  const Protocol* proto = nullptr;
  learning::Evaluation ev;
};

std::string pct(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << 100.0 * v;
  return s.str();
}

std::string safeName(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s;
}

void writeText(const fs::path& path, const std::string& text) { writeFileDurably(path.string(), text); }

// Mean ± 1 sd of a block's PDF over each class's views.
void plotClassPdfs(const FeatureTable& t, const learning::Labels& labels, const std::string& block, const fs::path& dir) {
  for (const auto& c : learning::classPdfs(t, labels, block)) {
    ui::LineChart chart;
    chart.title = block + " of " + c.label + " (" + std::to_string(c.views) + " views): mean ± 1 sd";
    chart.x_label = "bin";
    chart.y_label = "probability";
    ui::Series mean{"mean", {}, {}}, hi{"+1 sd", {}, {}}, lo{"-1 sd", {}, {}};
    for (std::size_t b = 0; b < c.mean.size(); ++b) {
      for (auto* s : {&mean, &hi, &lo}) s->x.push_back(static_cast<double>(b));
      mean.y.push_back(c.mean[b]);
      hi.y.push_back(c.mean[b] + c.sd[b]);
      lo.y.push_back(std::max(0.0, c.mean[b] - c.sd[b]));
    }
    chart.series = {mean, hi, lo};
    chart.y_min = 0;
    ui::saveChartPng(chart, (dir / (safeName(block + "_" + c.label) + ".png")).string(), 640, 400);
  }
}

int runEvaluate(const EvaluateArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  const auto sets = splitList(a.features);
  const auto classifiers = splitList(a.classifiers);
  const auto protocol_names = splitList(a.protocols);
  std::vector<int> bins_list;
  for (const auto& b : splitList(a.bins)) bins_list.push_back(std::stoi(b));
  if (bins_list.empty()) bins_list.push_back(a.flags.options.histogram.bins);
  if (sets.empty() || classifiers.empty() || protocol_names.empty())
    throw Error("evaluate needs at least one feature set, classifier and protocol");
  for (const auto& c : classifiers) {
    learning::ClassifierParams p = a.params;
    p.kind = c;
    learning::makeClassifier(p);  // unknown names fail before any work
  }
  const fs::path out(a.out);
  fs::create_directories(out / "confusion");
  fs::create_directories(out / "pdfs");

  std::vector<Row> rows;
  std::vector<std::unique_ptr<Protocol>> protocols;
  std::map<int, FeatureTable> tables;
  std::map<int, double> describe_s;
  for (int bins : bins_list) {
    DescriptorOptions options = a.flags.options;
    options.histogram.bins = bins;
    const auto t0 = std::chrono::steady_clock::now();
    tables[bins] = datasetFeatures(a.dataset, options, a.jobs, a.quiet);
    describe_s[bins] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const FeatureTable& t = tables[bins];
    for (const auto& set : sets)
      for (const auto& b : learning::featureSetBlocks(set))
        if (t.offset(b) < 0) throw Error("feature set '" + set + "': unknown block '" + b + "'");
    for (const auto& pn : protocol_names) {
      protocols.push_back(std::make_unique<Protocol>(learning::makeProtocol(pn, t, a.split_seed)));
      for (const auto& set : sets)
        for (const auto& c : classifiers) rows.push_back({bins, pn, set, c, protocols.back().get(), {}});
    }
  }
  std::size_t total_folds = 0;
  for (const auto& r : rows) total_folds += r.proto->folds.size();
  Progress progress("evaluate", total_folds, !a.quiet);
  for (auto& r : rows) {
    learning::ClassifierParams p = a.params;
    p.kind = r.classifier;
    r.ev = learning::evaluateFolds(tables[r.bins], learning::featureSetBlocks(r.features), r.proto->labels.of_row,
                                   static_cast<int>(r.proto->labels.names.size()), r.proto->folds, p, a.jobs,
                                   [&] { progress.advance(); });
  }
  progress.finish();
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // CSV and JSON: every row.
  std::ostringstream csv;
  csv << "bins,protocol,label,features,classifier,folds,test_views,accuracy_mean,accuracy_std,"
         "train_ms_per_view,predict_ms_per_view\n";
  nlohmann::json js;
  js["dataset"] = a.dataset;
  js["seconds"] = total_s;
  for (const auto& r : rows) {
    std::size_t tested = 0;
    nlohmann::json folds = nlohmann::json::array();
    for (const auto& f : r.ev.folds) {
      tested += f.test_views;
      folds.push_back({{"name", f.name}, {"accuracy", f.accuracy()}, {"train_views", f.train_views},
                       {"test_views", f.test_views}});
    }
    csv << r.bins << ',' << r.protocol << ',' << r.proto->labels.kindName() << ',' << r.features << ',' << r.classifier
        << ',' << r.ev.folds.size() << ',' << tested << ',' << r.ev.mean() << ',' << r.ev.stddev() << ','
        << r.ev.trainMsPerView() << ',' << r.ev.predictMsPerView() << '\n';
    js["rows"].push_back({{"bins", r.bins}, {"protocol", r.protocol}, {"label", r.proto->labels.kindName()},
                          {"features", r.features}, {"classifier", r.classifier}, {"accuracy_mean", r.ev.mean()},
                          {"accuracy_std", r.ev.stddev()}, {"train_ms_per_view", r.ev.trainMsPerView()},
                          {"predict_ms_per_view", r.ev.predictMsPerView()}, {"folds", folds}});
  }
  writeText(out / "report.csv", csv.str());
  writeText(out / "report.json", js.dump(2) + "\n");

  // Markdown: one Table-2-style table per bin count.
  std::ostringstream md;
  md << "# keyturn evaluate: " << a.dataset << "\n\n";
  for (int bins : bins_list) {
    const FeatureTable& t = tables[bins];
    const learning::TableSummary s = learning::summarise(t, a.flags.options.low_keypoints);
    md << "## " << bins << " bins\n\n"
       << s.views << " views; ISS keypoints K per view: median " << s.k_median << " (" << s.k_min << "–" << s.k_max
       << "), " << s.low << " views with K < " << a.flags.options.low_keypoints << ", " << s.failed
       << " views without keypoint features. Features described in " << std::fixed << std::setprecision(1)
       << describe_s[bins] << " s (" << std::setprecision(1) << 1000.0 * describe_s[bins] / std::max<std::size_t>(1, s.views)
       << " ms/view wall; 0 when cached).\n\n";
    std::vector<std::string> missing;
    for (const auto& [b, n] : s.missing)
      if (n) missing.push_back(b + " " + std::to_string(n));
    if (!missing.empty()) {
      md << "Views missing a block (kept in every protocol; XGBoost treats the values as missing, the network as 0): ";
      for (std::size_t i = 0; i < missing.size(); ++i) md << (i ? ", " : "") << missing[i];
      md << ".\n\n";
    }
    md << "Accuracy % (mean ± sd over folds). Labels: instance for kfold and leave-elevation, category for "
          "leave-instance.\n\n| features |";
    for (const auto& pn : protocol_names)
      for (const auto& c : classifiers) md << ' ' << c << " " << pn << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < protocol_names.size() * classifiers.size(); ++i) md << "---|";
    md << "\n";
    for (const auto& set : sets) {
      md << "| " << set << " |";
      for (const auto& pn : protocol_names)
        for (const auto& c : classifiers)
          for (const auto& r : rows)
            if (r.bins == bins && r.protocol == pn && r.features == set && r.classifier == c)
              md << ' ' << pct(r.ev.mean()) << " ± " << pct(r.ev.stddev()) << " |";
      md << "\n";
    }
    md << "\n";
  }
  md << "Train time per training view (mean over rows): ";
  for (const auto& c : classifiers) {
    double ms = 0;
    int n = 0;
    for (const auto& r : rows)
      if (r.classifier == c) ms += r.ev.trainMsPerView(), ++n;
    md << c << " " << std::setprecision(3) << ms / std::max(1, n) << " ms; ";
  }
  md << "\nTotal wall time " << std::setprecision(0) << total_s << " s.\n\n";

  // Confusion matrices of the best row per protocol (and bin count).
  md << "## Confusion matrices (best row per protocol)\n\n";
  for (const auto& pn : protocol_names)
    for (int bins : bins_list) {
      const Row* best = nullptr;
      for (const auto& r : rows)
        if (r.protocol == pn && r.bins == bins && (!best || r.ev.mean() > best->ev.mean())) best = &r;
      if (!best) continue;
      const std::string file = "confusion/" + safeName(pn + "_" + std::to_string(bins) + "bins") + ".png";
      ui::saveConfusionPng({pn + ": " + best->features + ", " + best->classifier + " (" + pct(best->ev.mean()) + "%)",
                            best->proto->labels.names, best->ev.confusion},
                           (out / file).string());
      md << "- " << pn << ", " << bins << " bins: " << best->features << " with " << best->classifier << " → ["
         << file << "](" << file << ")\n";
    }

  // Per-class PDFs (instances) of the paper's main functions and a baseline.
  const FeatureTable& t0 = tables[bins_list.front()];
  const learning::Labels by_instance = learning::labelRows(t0, learning::LabelKind::Instance);
  for (const std::string block : {"kpd2", "gkpd2", "kpa3", "d2"}) plotClassPdfs(t0, by_instance, block, out / "pdfs");
  md << "\nPer-class PDFs (mean ± 1 sd over each instance's views): `pdfs/`.\n";

  // Bin-count sweep (the paper's Fig. 20).
  if (bins_list.size() > 1) {
    for (const auto& pn : protocol_names)
      for (const auto& c : classifiers) {
        ui::LineChart chart;
        chart.title = "Accuracy vs bins, " + c + ", " + pn;
        chart.x_label = "bins";
        chart.y_label = "accuracy %";
        for (const auto& set : sets) {
          ui::Series s{set, {}, {}};
          for (const auto& r : rows)
            if (r.protocol == pn && r.classifier == c && r.features == set)
              s.x.push_back(r.bins), s.y.push_back(100.0 * r.ev.mean());
          chart.series.push_back(s);
        }
        const std::string file = "bins_" + safeName(c + "_" + pn) + ".png";
        ui::saveChartPng(chart, (out / file).string());
        md << "- bin sweep " << c << ", " << pn << ": [" << file << "](" << file << ")\n";
      }
  }
  writeText(out / "report.md", md.str());
  if (a.json) std::cout << js.dump(2) << "\n";
  if (!a.quiet) std::cerr << "keyturn evaluate: " << rows.size() << " rows in " << formatDuration(total_s) << " → " << (out / "report.md").string() << "\n";
  return 0;
}

}  // namespace

Command addEvaluateCommand(CLI::App& app) {
  auto a = std::make_shared<EvaluateArgs>();
  auto* cmd = app.add_subcommand("evaluate", "Cross-validated accuracy per feature set, classifier and protocol (Table 2)");
  cmd->add_option("dataset", a->dataset, "Dataset folder (manifest.csv)")->required();
  cmd->add_option("--features", a->features,
                  "Feature sets, space- or comma-separated; '+' concatenates blocks (kpd2 kpd3 kpa3 gkpd1 gkpd2 "
                  "gkpcd2, u_* on random keypoints, d2 d3 a3, esf vfh ourcvfh)")
      ->capture_default_str();
  cmd->add_option("--classifier", a->classifiers, "xgboost, mlp or both")->capture_default_str();
  cmd->add_option("--protocol", a->protocols, "kfoldN, leave-elevation, leave-instance, fixed:FILE")
      ->capture_default_str();
  cmd->add_option("--split-seed", a->split_seed, "Seed of the k-fold shuffle")->capture_default_str();
  cmd->add_option("--out,-o", a->out, "Report folder")->required();
  cmd->add_option("--jobs,-j", a->jobs, "Parallel views / folds (default: all cores)");
  cmd->add_flag("--json", a->json, "Also print the report as JSON on standard output");
  cmd->add_flag("--quiet,-q", a->quiet, "No progress");
  a->flags.add(*cmd, false);
  // evaluate's --bins takes a list (the sweep of the paper's Fig. 20).
  cmd->remove_option(cmd->get_option("--bins"));
  cmd->add_option("--bins", a->bins, "Histogram bins; a list sweeps them, e.g. 16,32,64")->default_str("32");
  addClassifierOptions(*cmd, a->params);
  return {cmd, [a] { return runEvaluate(*a); }};
}

}  // namespace keyturn::app
