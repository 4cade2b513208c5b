#include "keyturn/learning/protocols.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "keyturn/core/error.h"

namespace keyturn::learning {

LabelKind parseLabelKind(const std::string& name) {
  if (name == "instance") return LabelKind::Instance;
  if (name == "category") return LabelKind::Category;
  throw Error("label " + name + ": expected instance or category");
}

Labels labelRows(const FeatureTable& t, LabelKind kind) {
  // An instance is (class, instance): datasets that number instances per class ("1", "2", … as
  // SR4K-D does) would otherwise merge different objects into one label. Its name stays the
  // instance's own where that is unique across classes, "class/instance" where it is not.
  std::map<std::string, std::set<std::string>> classes_of;
  for (const auto& r : t.rows) classes_of[r.instance].insert(r.cls);
  const auto key = [&](const FeatureRow& r) {
    if (kind == LabelKind::Category) return r.cls;
    return classes_of.at(r.instance).size() > 1 ? r.cls + "/" + r.instance : r.instance;
  };
  Labels l;
  l.kind = kind;
  std::set<std::string> names;
  for (const auto& r : t.rows) names.insert(key(r));
  l.names.assign(names.begin(), names.end());
  for (const auto& r : t.rows)
    l.of_row.push_back(static_cast<int>(std::lower_bound(l.names.begin(), l.names.end(), key(r)) - l.names.begin()));
  return l;
}

namespace {

std::vector<std::string> testList(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw Error(file + ": cannot read the list of test views");
  std::vector<std::string> test;
  for (std::string line; std::getline(in, line);) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.size() > 4 && line.compare(line.size() - 4, 4, ".pcd") == 0) line.resize(line.size() - 4);
    if (!line.empty() && line[0] != '#') test.push_back(line);
  }
  return test;
}

// The N of an open-set protocol's name PREFIX[N]: its groups of categories (5 without one).
int groupsOf(const std::string& name, const std::string& prefix) {
  if (name.size() == prefix.size()) return 5;
  try {
    std::size_t used = 0;
    const int n = std::stoi(name.substr(prefix.size()), &used);
    if (used == name.size() - prefix.size()) return n;
  } catch (const std::exception&) {
  }
  throw Error("protocol '" + name + "': expected " + prefix + " or " + prefix + "N, e.g. " + prefix + "5");
}

}  // namespace

Protocol makeProtocol(const std::string& name, const FeatureTable& t, std::uint64_t seed,
                      std::optional<LabelKind> label) {
  Protocol p;
  p.name = name;
  std::vector<std::string> ids, elevations, categories, instances;
  for (const auto& r : t.rows) {
    ids.push_back(r.id);
    elevations.push_back(r.elevation);
    categories.push_back(r.cls);
    instances.push_back(r.instance);
  }
  LabelKind kind = LabelKind::Instance;
  if (name.rfind("kfold", 0) == 0) {
    int k = 0;
    try {
      k = std::stoi(name.substr(5));
    } catch (const std::exception&) {
      throw Error("protocol '" + name + "': expected kfoldN, e.g. kfold10");
    }
    p.folds = kFold(t.rows.size(), k, seed);
  } else if (name == "leave-elevation") {
    p.folds = leaveOneGroupOut(elevations, "elevation");
  } else if (name == "leave-instance") {
    p.folds = leaveOneInstanceOut(categories, instances);
    kind = LabelKind::Category;
    label.reset();  // an instance never trained on can only be judged by its category
  } else if (name.rfind("open-set-instance", 0) == 0) {
    p.folds = openSetInstanceFolds(categories, instances, groupsOf(name, "open-set-instance"), seed);
    kind = LabelKind::Category;
    label.reset();  // an instance never trained on can only be named by its category
  } else if (name.rfind("open-set", 0) == 0) {
    p.folds = openSetFolds(categories, elevations, groupsOf(name, "open-set"), seed);
  } else if (name.rfind("fixed:", 0) == 0) {
    p.folds = {fixedSplit(ids, testList(name.substr(6)))};
  } else {
    throw Error("unknown protocol '" + name + "' (kfoldN, leave-elevation, leave-instance, open-set[N], open-set-instance[N], fixed:FILE)");
  }
  p.labels = labelRows(t, label.value_or(kind));
  return p;
}

TableSummary summarise(const FeatureTable& t, int low_keypoints) {
  TableSummary s;
  s.views = t.rows.size();
  std::vector<int> ks;
  for (const auto& r : t.rows) {
    if (r.keypoints >= 0) ks.push_back(r.keypoints);
    else ++s.failed;
    if (r.keypoints >= 0 && r.keypoints < low_keypoints) ++s.low;
    for (const auto& b : t.blocks)
      if (std::isnan(r.values[static_cast<std::size_t>(t.offset(b))])) ++s.missing[b];
  }
  std::sort(ks.begin(), ks.end());
  if (!ks.empty()) {
    s.k_min = ks.front();
    s.k_max = ks.back();
    s.k_median = ks[ks.size() / 2];
  }
  return s;
}

std::vector<ClassPdf> classPdfs(const FeatureTable& t, const Labels& labels, const std::string& block) {
  std::vector<ClassPdf> out;
  const int o = t.offset(block);
  if (o < 0) return out;
  const int bins = t.blockSize(block);
  for (std::size_t c = 0; c < labels.names.size(); ++c) {
    std::vector<double> sum(bins, 0), sq(bins, 0);
    int n = 0;
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      if (labels.of_row[r] != static_cast<int>(c) || std::isnan(t.rows[r].values[static_cast<std::size_t>(o)])) continue;
      ++n;
      for (int b = 0; b < bins; ++b) {
        const double v = t.rows[r].values[static_cast<std::size_t>(o + b)];
        sum[b] += v;
        sq[b] += v * v;
      }
    }
    if (n == 0) continue;
    ClassPdf pdf{labels.names[c], n, {}, {}};
    for (int b = 0; b < bins; ++b) {
      const double m = sum[b] / n;
      pdf.mean.push_back(m);
      pdf.sd.push_back(std::sqrt(std::max(0.0, sq[b] / n - m * m)));
    }
    out.push_back(std::move(pdf));
  }
  return out;
}

}  // namespace keyturn::learning
