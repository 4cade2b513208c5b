#include "fold_views.h"

#include <algorithm>
#include <cmath>

#include "keyturn/learning/fusion_evaluation.h"

namespace keyturn::learning::detail {

std::string captureGroupOf(const FeatureRow& row) { return row.instance + "/" + row.elevation; }

TrainedFold trainFold(const FeatureTable& t, const std::vector<double>& az, const std::vector<std::string>& blocks,
                      const Labels& labels, const Fold& fold, const ClassifierParams& params, double bin_deg) {
  const int classes = static_cast<int>(labels.names.size());
  TrainedFold out;
  std::vector<std::string> groups;
  for (auto r : fold.train) {
    if (!std::isfinite(az[r])) continue;
    out.train.push_back(r);
    out.y.push_back(labels.of_row[r]);
    out.azimuth_deg.push_back(az[r]);
    groups.push_back(captureGroupOf(t.rows[r]));
  }
  out.x = t.select(blocks, out.train);
  out.classifier = makeClassifier(params);
  out.classifier->fit(out.x, out.y, classes);
  out.references = fitPoseReferences(out.x, out.y, out.azimuth_deg, groups, classes, bin_deg);
  return out;
}

FoldViews predictTestViews(const TrainedFold& trained, const FeatureTable& t, const std::vector<double>& az,
                           const std::vector<std::string>& blocks, const Labels& labels, const Fold& fold) {
  const Matrix xtest = t.select(blocks, fold.test);
  const Matrix p = trained.classifier->predictProba(xtest);
  FoldViews out;
  for (std::size_t k = 0; k < fold.test.size(); ++k) {
    const std::size_t r = fold.test[k];
    const auto row = static_cast<Eigen::Index>(k);
    FusionView v;
    v.probabilities.assign(p.row(row).data(), p.row(row).data() + p.cols());
    v.azimuth_deg = az[r];
    v.pose = poseEvidence(trained.references, xtest.row(row));
    Eigen::Index best = 0;
    p.row(row).maxCoeff(&best);
    out.single_correct += static_cast<int>(best) == labels.of_row[r];
    out.views.push_back(std::move(v));
    out.truth.push_back(labels.of_row[r]);
    out.group.push_back(captureGroupOf(t.rows[r]));
  }
  return out;
}

GroupedViews groupsByAngle(const std::vector<FusionView>& views, const std::vector<std::string>& group) {
  GroupedViews out;
  for (std::size_t i = 0; i < views.size(); ++i)
    if (std::isfinite(views[i].azimuth_deg)) out[group[i]].push_back({views[i].azimuth_deg, static_cast<int>(i)});
  return out;
}

int viewAt(const std::vector<std::pair<double, int>>& members, double a, double tolerance) {
  int best = -1;
  double best_d = tolerance;
  for (const auto& [azimuth, i] : members) {
    const double d = std::fmod(std::abs(azimuth - a), 360.0);
    const double circular = std::min(d, 360.0 - d);
    if (circular <= best_d) best_d = circular, best = i;
  }
  return best;
}

std::vector<int> viewsAtOffsets(const std::vector<std::pair<double, int>>& members, double start_deg,
                                const std::vector<double>& offsets, double tolerance) {
  std::vector<int> seq;
  for (double off : offsets) {
    const int i = viewAt(members, start_deg + off, tolerance);
    if (i < 0) break;
    seq.push_back(i);
  }
  return seq;
}

}  // namespace keyturn::learning::detail
