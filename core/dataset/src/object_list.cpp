#include "keyturn/dataset/object_list.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

#include "keyturn/core/error.h"

namespace fs = std::filesystem;

namespace keyturn::dataset {

namespace {

std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
      else if (c == '"') quoted = false;
      else cur += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// The list's rows as their named columns (in the order asked), after checking the header has them.
std::vector<std::vector<std::string>> readColumns(const std::string& path, const std::vector<std::string>& names,
                                                  const char* need) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the object list");
  std::string line;
  if (!std::getline(in, line)) throw Error(path + ": empty object list");
  const auto header = csvFields(line);
  std::vector<int> at;
  for (const auto& name : names) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw Error(path + ": needs " + need + " columns");
    at.push_back(static_cast<int>(it - header.begin()));
  }
  std::vector<std::vector<std::string>> out;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty() || line == "\r") continue;
    const auto f = csvFields(line);
    if (static_cast<int>(f.size()) <= *std::max_element(at.begin(), at.end()))
      throw Error(path + ": line " + std::to_string(n) + ": too few columns");
    std::vector<std::string> row;
    for (int i : at) row.push_back(f[i]);
    out.push_back(row);
  }
  if (out.empty()) throw Error(path + ": no objects listed");
  return out;
}

}  // namespace

std::vector<ObjectRow> readObjectList(const std::string& path) {
  const fs::path base = fs::path(path).parent_path();
  std::vector<ObjectRow> out;
  for (const auto& r : readColumns(path, {"class", "instance", "mesh"}, "class, instance and mesh")) {
    fs::path mesh = r[2];
    if (mesh.is_relative()) mesh = base / mesh;
    out.push_back({r[0], r[1], mesh.string()});
  }
  return out;
}

std::map<std::string, std::string> readInstanceClasses(const std::string& path) {
  std::map<std::string, std::string> out;
  for (const auto& r : readColumns(path, {"instance", "class"}, "class and instance")) {
    const auto [it, fresh] = out.emplace(r[0], r[1]);
    if (!fresh && it->second != r[1])
      throw Error(path + ": instance " + r[0] + " listed in two classes (" + it->second + ", " + r[1] + ")");
  }
  return out;
}

}  // namespace keyturn::dataset
