#include "keyturn/learning/splits.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <unordered_set>

#include "keyturn/core/error.h"

namespace keyturn::learning {

std::vector<Fold> kFold(std::size_t n, int k, std::uint64_t seed) {
  if (k < 2) throw Error("k-fold needs k >= 2 (got " + std::to_string(k) + ")");
  if (n < static_cast<std::size_t>(k))
    throw Error("k-fold with k = " + std::to_string(k) + " needs at least k rows (got " + std::to_string(n) + ")");
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<Fold> folds(static_cast<std::size_t>(k));
  for (int f = 0; f < k; ++f) {
    folds[f].name = "fold " + std::to_string(f + 1);
    // Fold f takes positions [f n / k, (f + 1) n / k): sizes differ by at most one.
    const std::size_t lo = f * n / k, hi = (f + 1) * n / k;
    for (std::size_t p = 0; p < n; ++p) (p >= lo && p < hi ? folds[f].test : folds[f].train).push_back(order[p]);
    std::sort(folds[f].test.begin(), folds[f].test.end());
    std::sort(folds[f].train.begin(), folds[f].train.end());
  }
  return folds;
}

std::vector<Fold> leaveOneGroupOut(const std::vector<std::string>& groups, const std::string& label) {
  const std::set<std::string> distinct(groups.begin(), groups.end());
  if (distinct.size() < 2)
    throw Error("leave-one-" + label + "-out needs at least two " + label + "s (the data has " +
                std::to_string(distinct.size()) + ")");
  std::vector<Fold> folds;
  for (const auto& g : distinct) {
    Fold f;
    f.name = label + " " + g;
    for (std::size_t i = 0; i < groups.size(); ++i) (groups[i] == g ? f.test : f.train).push_back(i);
    folds.push_back(std::move(f));
  }
  return folds;
}

std::vector<Fold> leaveOneInstanceOut(const std::vector<std::string>& categories,
                                      const std::vector<std::string>& instances) {
  if (categories.size() != instances.size()) throw Error("leave-one-instance-out: one category per row is needed");
  std::map<std::string, std::set<std::string>> per_category;
  for (std::size_t i = 0; i < categories.size(); ++i) per_category[categories[i]].insert(instances[i]);
  std::vector<Fold> folds;
  for (const auto& [category, members] : per_category) {
    if (members.size() < 2) continue;
    for (const auto& inst : members) {
      Fold f;
      f.name = "instance " + inst;
      for (std::size_t i = 0; i < instances.size(); ++i)
        (instances[i] == inst && categories[i] == category ? f.test : f.train).push_back(i);
      folds.push_back(std::move(f));
    }
  }
  if (folds.empty())
    throw Error("leave-one-instance-out needs a category with at least two instances (none has)");
  return folds;
}

Fold fixedSplit(const std::vector<std::string>& ids, const std::vector<std::string>& test_ids) {
  const std::unordered_set<std::string> wanted(test_ids.begin(), test_ids.end());
  std::unordered_set<std::string> seen;
  Fold f;
  f.name = "fixed split";
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (wanted.count(ids[i])) {
      f.test.push_back(i);
      seen.insert(ids[i]);
    } else {
      f.train.push_back(i);
    }
  }
  for (const auto& id : test_ids)
    if (!seen.count(id)) throw Error("fixed split: test view '" + id + "' is not in the dataset");
  if (f.train.empty()) throw Error("fixed split: every view is a test view, nothing is left to train on");
  return f;
}

std::vector<Fold> innerFolds(const std::vector<Fold>& outer, std::size_t i, int max_inner) {
  std::vector<std::size_t> others;
  for (std::size_t j = 0; j < outer.size(); ++j)
    if (j != i) others.push_back(j);
  const std::size_t n = std::min(others.size(), static_cast<std::size_t>(std::max(0, max_inner)));
  std::vector<Fold> inner;
  for (std::size_t k = 0; k < n; ++k) {
    const Fold& o = outer[others[k * others.size() / n]];
    Fold f;
    f.name = o.name;
    std::set_intersection(o.test.begin(), o.test.end(), outer[i].train.begin(), outer[i].train.end(),
                          std::back_inserter(f.test));
    std::set_difference(outer[i].train.begin(), outer[i].train.end(), f.test.begin(), f.test.end(),
                        std::back_inserter(f.train));
    if (!f.test.empty() && !f.train.empty()) inner.push_back(std::move(f));
  }
  return inner;
}

std::vector<int> categoryGroups(const std::vector<std::string>& distinct_categories, int groups, std::uint64_t seed) {
  std::vector<std::size_t> order(distinct_categories.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  const std::size_t g = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, groups)), order.size());
  std::vector<int> group(order.size(), 0);
  for (std::size_t p = 0; p < order.size(); ++p) group[order[p]] = static_cast<int>(p % g);
  return group;
}

namespace {

// The distinct categories open-set folds deal into groups, in name order; throws keyturn::Error for
// fewer than three (a fold must train on two) or fewer than two groups.
std::vector<std::string> openSetCategories(const std::vector<std::string>& categories, int groups) {
  const std::set<std::string> distinct(categories.begin(), categories.end());
  if (distinct.size() < 3)
    throw Error("open-set folds leave categories out: they need at least 3 categories (the data has " +
                std::to_string(distinct.size()) + ")");
  if (groups < 2) throw Error("open-set folds need at least 2 groups of categories (got " + std::to_string(groups) + ")");
  return std::vector<std::string>(distinct.begin(), distinct.end());
}

}  // namespace

std::vector<Fold> openSetInstanceFolds(const std::vector<std::string>& categories,
                                       const std::vector<std::string>& instances, int groups, std::uint64_t seed) {
  if (categories.size() != instances.size()) throw Error("open-set instance folds: one instance per row is needed");
  const std::vector<std::string> distinct = openSetCategories(categories, groups);
  std::map<std::string, std::vector<std::string>> members;  // category -> its instances, in name order
  for (std::size_t r = 0; r < categories.size(); ++r) members[categories[r]].push_back(instances[r]);
  for (auto& [c, m] : members) {
    std::sort(m.begin(), m.end());
    m.erase(std::unique(m.begin(), m.end()), m.end());
  }
  const std::vector<int> group_of = categoryGroups(distinct, groups, seed);
  const int g_count = *std::max_element(group_of.begin(), group_of.end()) + 1;
  std::vector<Fold> folds;
  for (int g = 0; g < g_count; ++g) {
    Fold f;
    std::string left_out, unseen;
    std::map<std::string, std::string> held;  // category -> its instance tested
    for (std::size_t c = 0; c < distinct.size(); ++c) {
      const auto& m = members.at(distinct[c]);
      if (group_of[c] == g) left_out += (left_out.empty() ? "" : "+") + distinct[c];
      else if (m.size() >= 2) {
        held[distinct[c]] = m[static_cast<std::size_t>(g) % m.size()];
        unseen += (unseen.empty() ? "" : "+") + held[distinct[c]];
      }
    }
    if (held.empty()) continue;
    f.name = "unknown " + left_out + ", unseen " + unseen;
    for (std::size_t r = 0; r < categories.size(); ++r) {
      const auto c = std::lower_bound(distinct.begin(), distinct.end(), categories[r]) - distinct.begin();
      const auto h = held.find(categories[r]);
      if (group_of[static_cast<std::size_t>(c)] == g) f.unknown.push_back(r);
      else (h != held.end() && h->second == instances[r] ? f.test : f.train).push_back(r);
    }
    folds.push_back(std::move(f));
  }
  if (folds.empty())
    throw Error("open-set instance folds need a category with at least two instances outside a left-out group (none has)");
  return folds;
}

std::vector<Fold> openSetFolds(const std::vector<std::string>& categories, const std::vector<std::string>& elevations,
                               int groups, std::uint64_t seed) {
  const std::vector<std::string> distinct = openSetCategories(categories, groups);
  const std::vector<int> group_of = categoryGroups(distinct, groups, seed);
  const int g_count = *std::max_element(group_of.begin(), group_of.end()) + 1;
  const std::set<std::string> elevation_set(elevations.begin(), elevations.end());
  const std::vector<std::string> elevation_list(elevation_set.begin(), elevation_set.end());
  const bool by_elevation = elevation_list.size() >= 2 && elevations.size() == categories.size();
  std::vector<int> part(categories.size(), 0);  // which fold tests the row, if known
  if (by_elevation) {
    for (std::size_t r = 0; r < categories.size(); ++r)
      part[r] = static_cast<int>(std::lower_bound(elevation_list.begin(), elevation_list.end(), elevations[r]) -
                                 elevation_list.begin());
  } else {
    std::vector<std::size_t> order(categories.size());
    std::iota(order.begin(), order.end(), 0);
    std::mt19937_64 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t p = 0; p < order.size(); ++p) part[order[p]] = static_cast<int>(p % static_cast<std::size_t>(g_count));
  }
  std::vector<Fold> folds(static_cast<std::size_t>(g_count));
  for (int g = 0; g < g_count; ++g) {
    Fold& f = folds[static_cast<std::size_t>(g)];
    const int tested = by_elevation ? g % static_cast<int>(elevation_list.size()) : g;
    std::string left_out;
    for (std::size_t c = 0; c < distinct.size(); ++c)
      if (group_of[c] == g) left_out += (left_out.empty() ? "" : "+") + distinct[c];
    f.name = "unknown " + left_out + (by_elevation ? ", elevation " + elevation_list[static_cast<std::size_t>(tested)] : "");
    for (std::size_t r = 0; r < categories.size(); ++r) {
      const auto c = std::lower_bound(distinct.begin(), distinct.end(), categories[r]) - distinct.begin();
      if (group_of[static_cast<std::size_t>(c)] == g) f.unknown.push_back(r);
      else (part[r] == tested ? f.test : f.train).push_back(r);
    }
  }
  return folds;
}

}  // namespace keyturn::learning
