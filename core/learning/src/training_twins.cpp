#include "keyturn/learning/training_twins.h"

#include <algorithm>
#include <unordered_map>

#include "keyturn/core/error.h"

namespace keyturn::learning {

TwinRows appendTwins(FeatureTable& table, const FeatureTable& given_extra, const std::string& extra_name) {
  FeatureTable extra = given_extra;  // an older cache may lack a block the other has: the blocks both have
  FeatureTable mine = table;
  keepCommonBlocks(mine, extra);
  checkSameFeatures(mine, extra, extra_name);
  table = std::move(mine);
  std::unordered_map<std::string, std::size_t> row_of;
  for (std::size_t r = 0; r < table.rows.size(); ++r) row_of.emplace(table.rows[r].id, r);
  TwinRows twins(table.rows.size());
  table.rows.reserve(table.rows.size() + extra.rows.size());
  for (const auto& x : extra.rows) {
    const auto it = row_of.find(x.id);
    if (it == row_of.end()) throw Error(extra_name + ": view " + x.id + " is not a view of the dataset");
    const FeatureRow& original = table.rows[it->second];
    if (x.cls != original.cls || x.instance != original.instance)
      throw Error(extra_name + ": view " + x.id + " is " + x.cls + "/" + x.instance + ", in the dataset " +
                  original.cls + "/" + original.instance);
    twins[it->second].push_back(table.rows.size());
    table.rows.push_back(x);
  }
  return twins;
}

std::vector<std::size_t> withTwins(const std::vector<std::size_t>& rows, const TwinRows& twins) {
  std::vector<std::size_t> out = rows;
  if (twins.empty()) return out;
  for (std::size_t r : rows)
    for (std::size_t t : twins.at(r)) out.push_back(t);
  return out;
}

std::vector<int> labelsWithTwins(std::vector<int> labels, const TwinRows& twins) {
  std::size_t rows = labels.size();
  for (const auto& of_row : twins)
    for (std::size_t t : of_row) rows = std::max(rows, t + 1);
  labels.resize(rows, -1);
  for (std::size_t r = 0; r < twins.size(); ++r)
    for (std::size_t t : twins[r]) labels[t] = labels[r];
  return labels;
}

}  // namespace keyturn::learning
