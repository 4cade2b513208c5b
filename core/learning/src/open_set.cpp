#include "keyturn/learning/open_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "keyturn/core/error.h"
#include "keyturn/core/median.h"
#include "keyturn/learning/feature_cache.h"
#include "reference_value_json.h"
#include "standardised_views.h"

namespace keyturn::learning {

std::string answerName(Answer a) {
  switch (a) {
    case Answer::Class: return "class";
    case Answer::Unknown: return "unknown";
    case Answer::NoObject: return "no object";
  }
  return "?";
}

namespace {

// Throws "open-set WHAT 'VALUE' is not one of A, B, C" unless value is one of `choices`.
void checkChoice(const std::vector<std::string>& choices, const std::string& value, const std::string& what) {
  if (std::find(choices.begin(), choices.end(), value) != choices.end()) return;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  throw Error("open-set " + what + " '" + value + "' is not one of " + list);
}

}  // namespace

const std::vector<std::string>& openSetMethods() {
  static const std::vector<std::string> methods = {"max-probability", "knn", "knn-relative"};
  return methods;
}

void checkOpenSetMethod(const std::string& method) { checkChoice(openSetMethods(), method, "method"); }

bool keepsReferences(const std::string& method) { return method == "knn" || method == "knn-relative"; }

const std::vector<std::string>& openSetDistances() {
  static const std::vector<std::string> distances = {"rms", "l1", "chi2"};
  return distances;
}

void checkOpenSetDistance(const std::string& distance) { checkChoice(openSetDistances(), distance, "distance"); }

void checkOpenSetDistanceFor(const std::string& distance, const std::vector<std::string>& blocks) {
  checkOpenSetDistance(distance);
  if (distance == "rms") return;
  for (const auto& b : blocks) {
    const auto kind = parseBlockName(b).kind;
    if (kind == BlockName::Peer || kind == BlockName::Size)
      throw Error("open-set distance '" + distance + "' compares PDFs, and block '" + b +
                  "' is not one: use the rms distance");
  }
}

void checkOpenSetMethodsFor(const std::vector<std::string>& methods, const std::vector<std::string>& blocks) {
  for (const auto& m : methods) {
    if (!keepsReferences(m)) continue;
    for (const auto& b : blocks)
      if (parseBlockName(b).kind == BlockName::KeypointSet)
        throw Error("open-set method '" + m + "' measures distances between feature rows, and block '" + b +
                    "' lists keypoints in no fixed order: use the max-probability method");
  }
}

namespace {

// The rows as described, for the PDF distances (l1, chi2): a standardised value times the column's
// spread plus its mean (a missing value stands at the mean in both forms). A value the model file
// keeps as 0's (4 decimals, reference_value_json.h) is 0: an empty bin came back as ±5e-5 spreads,
// which L1 and χ² count in full, and a training view then lay farther from its own reference than
// from its neighbours. The zero is compared as a double, as the file writes it (rounded into a float
// it moved the AUROC in the 6th digit). Converted once per row, not once per pair: the pair loops of
// fitting and scoring converted both rows for every pair (an evaluate of 1,944 views, χ², took 47.2 s
// instead of 43.9).
using DescribedRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

DescribedRows described(const OpenSet& s, const Matrix& rows) {
  DescribedRows out(rows.rows(), rows.cols());
  for (Eigen::Index k = 0; k < rows.cols(); ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const double zero = referenceValue((0.f - s.mean[kk]) / s.scale[kk]);
    for (Eigen::Index r = 0; r < rows.rows(); ++r) {
      const float v = rows(r, k);
      out(r, k) = referenceValue(v) == zero ? 0.0 : std::max(0.0, static_cast<double>(v) * s.scale[kk] + s.mean[kk]);
    }
  }
  return out;
}

double pdfDistance(bool l1, const double* p, const double* q, Eigen::Index n) {
  double sum = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (l1) sum += std::abs(p[k] - q[k]);
    else if (p[k] + q[k] > 0) sum += 0.5 * (p[k] - q[k]) * (p[k] - q[k]) / (p[k] + q[k]);
  }
  return sum;
}

// The scorer's distance between rows of a set of standardised rows: RMS on the rows themselves, the
// PDF distances on the rows as described (converted once, when the set is made).
class RowDistances {
 public:
  RowDistances(const OpenSet& s, const Matrix& rows)
      : rows_(rows), rms_(s.distance == "rms"), l1_(s.distance == "l1") {
    if (!rms_) described_ = described(s, rows);
  }
  double operator()(Eigen::Index a, Eigen::Index b) const {
    if (rms_) return detail::rmsDistance(rows_.row(a), rows_.row(b));
    return pdfDistance(l1_, described_.row(a).data(), described_.row(b).data(), described_.cols());
  }
  // Between row a and another set's row b (both made by the same scorer).
  double operator()(Eigen::Index a, const RowDistances& other, Eigen::Index b) const {
    if (rms_) return detail::rmsDistance(rows_.row(a), other.rows_.row(b));
    return pdfDistance(l1_, described_.row(a).data(), other.described_.row(b).data(), described_.cols());
  }

 private:
  const Matrix& rows_;
  bool rms_, l1_;
  DescribedRows described_;
};

}  // namespace

double openSetDistance(const OpenSet& s, const Eigen::RowVectorXf& a, const Eigen::RowVectorXf& b) {
  if (s.distance == "rms") return detail::rmsDistance(a, b);
  Matrix pair(2, a.size());
  pair.row(0) = a, pair.row(1) = b;
  return RowDistances(s, pair)(0, 1);
}

const std::vector<std::string>& openSetScales() {
  static const std::vector<std::string> scales = {"pooled", "camera"};
  return scales;
}

void checkOpenSetScale(const std::string& scale_by) { checkChoice(openSetScales(), scale_by, "scale"); }

const std::vector<std::string>& openSetRules() {
  static const std::vector<std::string> rules = {"pooled", "per-group"};
  return rules;
}

void checkOpenSetRule(const std::string& rule) { checkChoice(openSetRules(), rule, "calibration rule"); }

const std::vector<std::string>& openSetSpreads() {
  static const std::vector<std::string> spreads = {"views", "instances"};
  return spreads;
}

void checkOpenSetSpread(const std::string& spread) { checkChoice(openSetSpreads(), spread, "class spread"); }

namespace {

// Each class's own scale for knn-relative: the median, over its training views, of the RMS
// distance to the nearest other training view of the class (how far a view of it lies from its
// neighbours: the sensor's noise on it and the turntable's step). Measured across capture groups
// (another instance or elevation) instead, known views were accepted more often but the
// calibrated rate held worse (docs/results.md, "Open-set answers"). A class with one view takes
// the median of the others. nearest (optional) receives each row's distance (NaN: its class has no other).
std::vector<float> classScales(const OpenSet& s, const std::vector<int>& y, std::vector<double>* nearest_of = nullptr) {
  const RowDistances distance(s, s.references);
  const int classes = y.empty() ? 0 : *std::max_element(y.begin(), y.end()) + 1;
  std::vector<std::vector<Eigen::Index>> rows_of(static_cast<std::size_t>(classes));
  for (std::size_t r = 0; r < y.size(); ++r) rows_of[static_cast<std::size_t>(y[r])].push_back(static_cast<Eigen::Index>(r));
  std::vector<float> scale(static_cast<std::size_t>(classes), std::nanf(""));
  std::vector<double> all;
  if (nearest_of) nearest_of->assign(y.size(), std::nan(""));
  for (std::size_t c = 0; c < rows_of.size(); ++c) {  // within each class only: the sum of n_c², not n²
    std::vector<double> nearest;
    for (Eigen::Index a : rows_of[c]) {
      double best = std::numeric_limits<double>::infinity();
      for (Eigen::Index b : rows_of[c])
        if (b != a) best = std::min(best, distance(a, b));
      if (std::isfinite(best)) nearest.push_back(best);
      if (nearest_of && std::isfinite(best)) (*nearest_of)[static_cast<std::size_t>(a)] = best;
    }
    if (nearest.empty()) continue;
    scale[c] = static_cast<float>(std::max(1e-6, upperMedian(nearest)));
    all.push_back(scale[c]);
  }
  const float fallback = all.empty() ? 1.f : static_cast<float>(upperMedian(all));
  for (float& v : scale)
    if (std::isnan(v)) v = fallback;
  return scale;
}

// The classes' scales drawn toward their median: s_c^p · median^(1-p) (p = 1 leaves them as they are).
void drawTowardMedian(std::vector<float>& scale, double p) {
  if (p == 1 || scale.empty()) return;
  const double median = upperMedian(std::vector<double>(scale.begin(), scale.end()));
  for (float& v : scale) v = static_cast<float>(std::pow(static_cast<double>(v), p) * std::pow(median, 1 - p));
}

// Each camera's factor: the median over its rows of (distance to the nearest other view of the class) /
// (the class's pooled scale). A camera whose views are sparser or noisier than the pool's (the SR4000's
// against the OpenNI2's) gets a factor above 1, so its known views are not judged by the other's spread.
std::map<std::string, float> cameraScales(const std::vector<std::string>& cameras, const std::vector<int>& y,
                                          const std::vector<double>& nearest, const std::vector<float>& class_scale) {
  std::map<std::string, std::vector<double>> ratios;
  for (std::size_t r = 0; r < y.size(); ++r)
    if (!cameras[r].empty() && std::isfinite(nearest[r]))
      ratios[cameras[r]].push_back(nearest[r] / class_scale[static_cast<std::size_t>(y[r])]);
  std::map<std::string, float> out;
  for (const auto& [camera, v] : ratios) out[camera] = static_cast<float>(std::max(1e-6, upperMedian(v)));
  return out;
}

// Each class's instance spread over its view spread: for a class of two or more instances, the median
// over its views of the distance to the nearest view of another of its instances, over the class's
// view scale `own`. A category model's unseen instance lies at the first distance from the references,
// not at the second (the sensor noise and the turntable step between neighbouring views of one
// instance). A single-instance class takes the median ratio of the others (1 when no class has two).
std::vector<double> instanceSpreadRatios(const OpenSet& s, const std::vector<int>& y,
                                         const std::vector<std::string>& instances, const std::vector<float>& own) {
  const RowDistances distance(s, s.references);
  std::vector<std::vector<Eigen::Index>> rows_of(own.size());
  for (std::size_t r = 0; r < y.size(); ++r) rows_of[static_cast<std::size_t>(y[r])].push_back(static_cast<Eigen::Index>(r));
  std::vector<double> ratio(own.size(), std::nan("")), measured;
  for (std::size_t c = 0; c < rows_of.size(); ++c) {
    std::vector<double> nearest;
    for (Eigen::Index a : rows_of[c]) {
      double best = std::numeric_limits<double>::infinity();
      for (Eigen::Index b : rows_of[c])
        if (instances[static_cast<std::size_t>(b)] != instances[static_cast<std::size_t>(a)])
          best = std::min(best, distance(a, b));
      if (std::isfinite(best)) nearest.push_back(best);
    }
    if (nearest.empty()) continue;  // one instance
    ratio[c] = std::max(1e-6, upperMedian(nearest)) / static_cast<double>(own[c]);
    measured.push_back(ratio[c]);
  }
  const double fallback = measured.empty() ? 1.0 : upperMedian(measured);
  for (double& v : ratio)
    if (std::isnan(v)) v = fallback;
  return ratio;
}

}  // namespace

OpenSet fitOpenSetScorer(const std::string& method, const Matrix& x, const std::vector<int>& y, int neighbours,
                         const std::string& scale_by, const std::vector<std::string>* cameras,
                         double class_scale_power, const std::string& class_spread,
                         const std::vector<std::string>* instances, const std::string& distance) {
  checkOpenSetMethod(method);
  checkOpenSetDistance(distance);
  checkOpenSetScale(scale_by);
  checkOpenSetSpread(class_spread);
  if (class_spread == "instances" && method == "knn-relative" && (!instances || instances->size() != y.size()))
    throw Error("open-set class spread 'instances' needs each training view's instance (" + std::to_string(y.size()) +
                " rows, " + std::to_string(instances ? instances->size() : 0) + " instances)");
  if (!(class_scale_power >= 0 && class_scale_power <= 1))
    throw Error("open-set class scale power must be within [0, 1], not " + std::to_string(class_scale_power));
  if (cameras && cameras->size() != y.size())
    throw Error("open-set scales: " + std::to_string(y.size()) + " rows but " + std::to_string(cameras->size()) + " cameras");
  OpenSet s;
  s.method = method;
  if (!keepsReferences(method)) return s;
  if (neighbours < 1) throw Error("knn open-set scores need at least one neighbour (not " + std::to_string(neighbours) + ")");
  if (static_cast<std::size_t>(x.rows()) != y.size()) throw Error("knn open-set scores: rows and labels differ in number");
  s.neighbours = neighbours;
  s.distance = distance;
  detail::fitStandardisation(x, s.mean, s.scale);
  s.references = detail::standardisedRows(x, s.mean, s.scale);
  s.reference_class = y;
  if (method != "knn-relative") return s;
  std::vector<double> nearest;
  s.class_scale = classScales(s, y, &nearest);
  const std::vector<float> own = s.class_scale;
  drawTowardMedian(s.class_scale, class_scale_power);
  s.class_scale_power = class_scale_power;
  s.scale_by = scale_by;
  if (scale_by == "camera" && cameras) s.camera_scale = cameraScales(*cameras, y, nearest, s.class_scale);
  s.class_spread = class_spread;
  if (class_spread == "instances") {  // after the camera factors: they compare cameras, not instances
    const std::vector<double> ratio = instanceSpreadRatios(s, y, *instances, own);
    for (std::size_t c = 0; c < s.class_scale.size(); ++c) s.class_scale[c] *= static_cast<float>(ratio[c]);
  }
  return s;
}

namespace {

// Mean distance from row v of `views` to the `k` nearest references of class c; NaN without any.
double nearestDistance(const OpenSet& s, const RowDistances& references, const RowDistances& views, Eigen::Index v,
                       int c) {
  std::vector<double> d;
  for (Eigen::Index r = 0; r < s.references.rows(); ++r)
    if (s.reference_class[static_cast<std::size_t>(r)] == c) d.push_back(references(r, views, v));
  if (d.empty()) return std::nan("");
  const std::size_t k = std::min(d.size(), static_cast<std::size_t>(s.neighbours));
  std::partial_sort(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(k), d.end());
  double sum = 0;
  for (std::size_t i = 0; i < k; ++i) sum += d[i];
  return sum / static_cast<double>(k);
}

}  // namespace

std::vector<double> openSetScores(const OpenSet& s, const Matrix& x, const Matrix& p,
                                  const std::vector<std::string>* cameras) {
  checkOpenSetMethod(s.method);
  if (p.rows() != x.rows()) throw Error("open-set scores: " + std::to_string(x.rows()) + " views but " +
                                        std::to_string(p.rows()) + " rows of probabilities");
  if (cameras && cameras->size() != static_cast<std::size_t>(x.rows()))
    throw Error("open-set scores: " + std::to_string(x.rows()) + " views but " + std::to_string(cameras->size()) + " cameras");
  std::vector<double> out(static_cast<std::size_t>(x.rows()), 0.0);
  if (s.method != "max-probability" && x.rows() > 0 && x.cols() != static_cast<Eigen::Index>(s.mean.size()))
    throw Error("knn open-set scores: the model has " + std::to_string(s.mean.size()) + " features, the view " +
                std::to_string(x.cols()));
  // The views standardised and, for the PDF distances, the views and references described, once.
  Matrix views;
  std::optional<RowDistances> references, view_rows;
  if (s.method != "max-probability" && x.rows() > 0) {
    views = detail::standardisedRows(x, s.mean, s.scale);
    references.emplace(s, s.references);
    view_rows.emplace(s, views);
  }
  for (Eigen::Index r = 0; r < x.rows(); ++r) {
    if (p.cols() == 0 || !p.row(r).allFinite()) continue;  // scores 0: rejected by any calibrated threshold
    Eigen::Index best = 0;
    const double top = p.row(r).maxCoeff(&best);
    if (s.method == "max-probability") {
      out[static_cast<std::size_t>(r)] = top;
      continue;
    }
    double d = nearestDistance(s, *references, *view_rows, r, static_cast<int>(best));
    if (s.method == "knn-relative")
      d = static_cast<std::size_t>(best) < s.class_scale.size()
              ? d / (s.class_scale[static_cast<std::size_t>(best)] *
                     (cameras ? s.cameraFactor((*cameras)[static_cast<std::size_t>(r)]) : 1.f))
              : std::nan("");
    out[static_cast<std::size_t>(r)] = std::isfinite(d) ? 1.0 / (1.0 + d) : 0.0;
  }
  return out;
}

double thresholdForFalseAccept(std::vector<double> u, double false_accept) {
  if (u.empty()) throw Error("open-set calibration: no views of unknown categories to set the threshold on");
  if (!(false_accept >= 0 && false_accept < 1))
    throw Error("open-set false-accept rate must be within [0, 1), not " + std::to_string(false_accept));
  std::sort(u.begin(), u.end(), std::greater<double>());
  // At most m unknowns may score >= threshold: just above the (m + 1)-th highest score.
  const auto m = static_cast<std::size_t>(std::floor(false_accept * static_cast<double>(u.size()) + 1e-9));
  return std::nextafter(u[std::min(m, u.size() - 1)], std::numeric_limits<double>::infinity());
}

double auroc(const std::vector<double>& known, const std::vector<double>& unknown) {
  if (known.empty() || unknown.empty()) return std::nan("");
  std::vector<double> u = unknown;
  std::sort(u.begin(), u.end());
  double sum = 0;
  for (double k : known) {
    const auto lo = std::lower_bound(u.begin(), u.end(), k), hi = std::upper_bound(u.begin(), u.end(), k);
    sum += static_cast<double>(lo - u.begin()) + 0.5 * static_cast<double>(hi - lo);
  }
  return sum / (static_cast<double>(known.size()) * static_cast<double>(u.size()));
}

RocCurve rocCurve(const std::vector<double>& known, const std::vector<double>& unknown) {
  RocCurve c;
  std::vector<std::pair<double, bool>> all;  // score, known
  for (double k : known) all.push_back({k, true});
  for (double u : unknown) all.push_back({u, false});
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  const double nk = std::max<std::size_t>(1, known.size()), nu = std::max<std::size_t>(1, unknown.size());
  double tk = 0, fu = 0;
  c.false_accept.push_back(0);
  c.true_accept.push_back(0);
  for (std::size_t i = 0; i < all.size(); ++i) {
    (all[i].second ? tk : fu) += 1;
    if (i + 1 < all.size() && all[i + 1].first == all[i].first) continue;  // one point per distinct score
    c.false_accept.push_back(fu / nu);
    c.true_accept.push_back(tk / nk);
  }
  return c;
}

}  // namespace keyturn::learning
