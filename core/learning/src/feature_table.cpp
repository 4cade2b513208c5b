#include "keyturn/learning/feature_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"

namespace keyturn::learning {

namespace {

constexpr const char* kMagic = "# keyturn-features 1";
constexpr int kLabelColumns = 6;  // id,class,instance,elevation,keypoints,problem

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream ls(line);
  while (std::getline(ls, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

bool plainField(const std::string& s) { return s.find_first_of(",\n\r") == std::string::npos; }

std::string clean(std::string s) {
  for (char& c : s)
    if (c == ',' || c == '\n' || c == '\r') c = ';';
  return s;
}

}  // namespace

int FeatureTable::width() const {
  int w = 0;
  for (int s : sizes) w += s;
  return w;
}

int FeatureTable::offset(const std::string& block) const {
  int o = 0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (blocks[b] == block) return o;
    o += sizes[b];
  }
  return -1;
}

int FeatureTable::blockSize(const std::string& block) const {
  for (std::size_t b = 0; b < blocks.size(); ++b)
    if (blocks[b] == block) return sizes[b];
  return 0;
}

Matrix FeatureTable::select(const std::vector<std::string>& wanted, const std::vector<std::size_t>& row_ids) const {
  std::vector<std::pair<int, int>> spans;  // offset, size
  int cols = 0;
  for (const auto& w : wanted) {
    const int o = offset(w);
    if (o < 0) throw Error("the feature cache has no '" + w + "' block");
    const int s = blockSize(w);
    spans.emplace_back(o, s);
    cols += s;
  }
  Matrix m(static_cast<Eigen::Index>(row_ids.size()), cols);
  for (std::size_t r = 0; r < row_ids.size(); ++r) {
    const auto& v = rows.at(row_ids[r]).values;
    int c = 0;
    for (const auto& [o, s] : spans)
      for (int k = 0; k < s; ++k) m(static_cast<Eigen::Index>(r), c++) = v[static_cast<std::size_t>(o + k)];
  }
  return m;
}

void saveFeatureTable(const std::string& path, const FeatureTable& t) {
  std::ostringstream out;
  out << kMagic << "\n";
  for (const auto& [k, v] : t.spec) {
    if (!plainField(k) || !plainField(v) || k.find('=') != std::string::npos)
      throw Error(path + ": feature parameter '" + k + "' cannot be stored");
    out << "# " << k << "=" << v << "\n";
  }
  out << "id,class,instance,elevation,keypoints,problem";
  for (std::size_t b = 0; b < t.blocks.size(); ++b)
    for (int k = 0; k < t.sizes[b]; ++k) out << "," << t.blocks[b] << "_" << k;
  out << "\n";
  const int width = t.width();
  char buf[32];
  for (const auto& r : t.rows) {
    for (const auto* f : {&r.id, &r.cls, &r.instance, &r.elevation})
      if (!plainField(*f)) throw Error(path + ": view '" + r.id + "' has a label with a comma or line break");
    if (static_cast<int>(r.values.size()) != width)
      throw Error(path + ": view '" + r.id + "' has " + std::to_string(r.values.size()) + " values, expected " +
                  std::to_string(width));
    out << r.id << "," << r.cls << "," << r.instance << "," << r.elevation << "," << r.keypoints << ","
        << clean(r.problem);
    for (float v : r.values) {
      std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));  // 9 digits: floats round-trip exactly
      out << "," << (std::isnan(v) ? "nan" : buf);
    }
    out << "\n";
  }
  writeFileDurably(path, out.str());
}

FeatureTable loadFeatureTable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the feature cache");
  FeatureTable t;
  std::string line;
  int n = 1;
  auto where = [&] { return path + ": line " + std::to_string(n) + ": "; };
  if (!std::getline(in, line) || line != kMagic) throw Error(path + ": not a keyturn feature cache (no '" + std::string(kMagic) + "' line)");
  for (++n; std::getline(in, line) && line.rfind("# ", 0) == 0; ++n) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) throw Error(where() + "a parameter line needs key=value");
    t.spec[line.substr(2, eq - 2)] = line.substr(eq + 1);
  }
  const auto header = splitCsv(line);
  if (header.size() < kLabelColumns || header[0] != "id" || header[5] != "problem")
    throw Error(where() + "the column header must start id,class,instance,elevation,keypoints,problem");
  for (std::size_t c = kLabelColumns; c < header.size(); ++c) {
    const auto us = header[c].rfind('_');
    if (us == std::string::npos || us == 0) throw Error(where() + "bad feature column '" + header[c].substr(0, 40) + "'");
    const std::string block = header[c].substr(0, us);
    const std::string index = header[c].substr(us + 1);
    if (t.blocks.empty() || t.blocks.back() != block) {
      if (std::find(t.blocks.begin(), t.blocks.end(), block) != t.blocks.end())
        throw Error(where() + "block '" + block.substr(0, 40) + "' is split");
      t.blocks.push_back(block);
      t.sizes.push_back(0);
    }
    if (index != std::to_string(t.sizes.back()))
      throw Error(where() + "column '" + header[c].substr(0, 40) + "' is out of order");
    ++t.sizes.back();
  }
  const std::size_t width = header.size() - kLabelColumns;
  std::set<std::string> ids;
  for (++n; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const auto cells = splitCsv(line);
    if (cells.size() != header.size())
      throw Error(where() + std::to_string(cells.size()) + " cells, the header has " + std::to_string(header.size()));
    FeatureRow r;
    r.id = cells[0];
    r.cls = cells[1];
    r.instance = cells[2];
    r.elevation = cells[3];
    r.problem = cells[5];
    if (r.id.empty() || r.cls.empty()) throw Error(where() + "a view needs an id and a class");
    if (!ids.insert(r.id).second) throw Error(where() + "view '" + r.id.substr(0, 80) + "' appears twice");
    try {
      std::size_t used = 0;
      r.keypoints = std::stoi(cells[4], &used);
      if (used != cells[4].size()) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw Error(where() + "bad keypoint count '" + cells[4].substr(0, 20) + "'");
    }
    r.values.resize(width);
    for (std::size_t c = 0; c < width; ++c) {
      const std::string& s = cells[kLabelColumns + c];
      char* end = nullptr;
      r.values[c] = std::strtof(s.c_str(), &end);
      if (s.empty() || *end != '\0')
        throw Error(where() + "bad value '" + s.substr(0, 20) + "' in column " + header[kLabelColumns + c]);
    }
    t.rows.push_back(std::move(r));
  }
  return t;
}

void checkSameFeatures(const FeatureTable& table, const FeatureTable& other, const std::string& other_name) {
  if (other.blocks != table.blocks || other.sizes != table.sizes)
    throw Error(other_name + ": its features have other blocks than the dataset's");
  for (const auto& [key, value] : table.spec) {
    const auto it = other.spec.find(key);
    if (it == other.spec.end() || it->second != value)
      throw Error(other_name + ": described with other parameters (" + key + " " +
                  (it == other.spec.end() ? std::string("missing") : it->second) + ", the dataset's " + value + ")");
  }
}

namespace {

FeatureTable withBlocks(const FeatureTable& t, const std::vector<std::string>& blocks) {
  FeatureTable out;
  out.spec = t.spec;
  for (const auto& b : blocks) out.blocks.push_back(b), out.sizes.push_back(t.blockSize(b));
  out.rows.reserve(t.rows.size());
  for (const auto& row : t.rows) {
    FeatureRow r = row;
    r.values.clear();
    for (const auto& b : blocks) {
      const auto from = row.values.begin() + t.offset(b);
      r.values.insert(r.values.end(), from, from + t.blockSize(b));
    }
    out.rows.push_back(std::move(r));
  }
  return out;
}

}  // namespace

bool hasBlocks(const FeatureTable& t, const std::vector<std::string>& blocks) {
  return std::all_of(blocks.begin(), blocks.end(), [&t](const std::string& b) { return t.offset(b) >= 0; });
}

void keepCommonBlocks(FeatureTable& a, FeatureTable& b) {
  if (a.blocks == b.blocks) return;
  if (!hasBlocks(b, a.blocks) && !hasBlocks(a, b.blocks)) return;  // not an older cache of the same blocks: checkSameFeatures refuses it
  std::vector<std::string> common;
  for (const auto& block : a.blocks)
    if (b.offset(block) >= 0) common.push_back(block);
  if (common != a.blocks) a = withBlocks(a, common);
  if (common != b.blocks) b = withBlocks(b, common);
}

void appendRows(FeatureTable& table, const FeatureTable& other, const std::string& other_name) {
  if (other.blocks != table.blocks) {
    FeatureTable mine = table, theirs = other;  // a refused dataset leaves the table as it was
    keepCommonBlocks(mine, theirs);
    checkSameFeatures(mine, theirs, other_name);
    mine.rows.insert(mine.rows.end(), theirs.rows.begin(), theirs.rows.end());
    table = std::move(mine);
    return;
  }
  checkSameFeatures(table, other, other_name);
  table.rows.insert(table.rows.end(), other.rows.begin(), other.rows.end());
}

FeatureTable mergeFeatureTables(const std::vector<FeatureTable>& shards, const std::vector<std::string>& names) {
  if (shards.empty()) throw Error("no feature cache shards to merge");
  FeatureTable out = shards.front();
  out.rows.clear();
  std::set<std::string> ids;
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const auto& sh = shards[s];
    if (sh.blocks != out.blocks || sh.sizes != out.sizes || sh.spec != out.spec)
      throw Error(names[s] + ": computed with other features or parameters than " + names[0]);
    for (const auto& r : sh.rows) {
      if (!ids.insert(r.id).second) throw Error(names[s] + ": view '" + r.id + "' is also in another shard");
      out.rows.push_back(r);
    }
  }
  return out;
}

namespace {

// A feature set split at `sep`; an empty part (also before a trailing separator) is "empty WHAT".
std::vector<std::string> splitFeatureSet(const std::string& set, char sep, const std::string& what) {
  std::vector<std::string> out;
  std::stringstream ss(set);
  for (std::string part; std::getline(ss, part, sep);) {
    if (part.empty()) throw Error("feature set '" + set + "': empty " + what);
    out.push_back(part);
  }
  if (!set.empty() && set.back() == sep) throw Error("feature set '" + set + "': empty " + what);
  return out;
}

}  // namespace

std::vector<std::string> featureSetBlocks(const std::string& set) {
  std::vector<std::string> out = splitFeatureSet(set, '+', "part");
  if (out.empty()) throw Error("empty feature set");
  return out;
}

std::vector<std::string> featureSetChoices(const std::string& set) {
  std::vector<std::string> out = splitFeatureSet(set, '|', "choice");
  if (out.empty()) throw Error("feature set '" + set + "': empty choice");
  return out;
}

}  // namespace keyturn::learning
