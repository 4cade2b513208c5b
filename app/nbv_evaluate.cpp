// keyturn evaluate --protocol nbv: next best view against fixed steps, accuracy against the number
// of views and under the stopping rule, under leave-instance and leave-elevation where the dataset
// has them (learning/nbv_evaluation.h runs and reports it). A protocol of its own rather than an
// option of --protocol fusion: its sequences are chosen view by view, it trains the inner folds
// that estimate the per-angle confusions, and its report answers another question.
#include <filesystem>
#include <iostream>

#include "fusion_options.h"
#include "keyturn/learning/nbv_evaluation.h"
#include "report_files.h"

namespace keyturn::app {

int runNbvEvaluate(const FusionEvaluateArgs& a) {
  checkOneFeatureSetAndClassifier(a, "nbv");
  const learning::NbvEvaluationOptions options = a.flags.nbvOptions();
  const PosedTable posed = posedTable(a, "nbv");
  learning::ClassifierParams params = a.params;
  params.kind = a.classifier;
  const auto blocks = learning::featureSetBlocks(a.features);
  std::vector<learning::NbvProtocolResult> results;
  for (const auto& p : posed.protocols) {
    if (!a.quiet) std::cerr << "keyturn evaluate: next best view under " << p << "\n";
    results.push_back(learning::evaluateNextBestView(posed.table, posed.azimuths, blocks, p, params, options, a.jobs));
  }
  const learning::NbvReport report = learning::nbvReport(results, a.dataset, a.features, a.classifier, options);
  writeReportFiles(a.out, report);
  if (a.json) std::cout << report.json;
  if (!a.quiet) std::cerr << "keyturn evaluate: next best view → " << (std::filesystem::path(a.out) / "report.md").string() << "\n";
  return 0;
}

}  // namespace keyturn::app
