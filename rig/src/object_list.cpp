#include "keyturn/rig/object_list.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"

namespace fs = std::filesystem;

namespace keyturn::rig {

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

}  // namespace

std::vector<ObjectRow> readObjectList(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the object list");
  std::string line;
  if (!std::getline(in, line)) throw Error(path + ": empty object list");
  const auto header = csvFields(line);
  int ic = -1, ii = -1, im = -1;
  for (int i = 0; i < static_cast<int>(header.size()); ++i) {
    if (header[i] == "class") ic = i;
    if (header[i] == "instance") ii = i;
    if (header[i] == "mesh") im = i;
  }
  if (ic < 0 || ii < 0 || im < 0) throw Error(path + ": needs class, instance and mesh columns");
  const fs::path base = fs::path(path).parent_path();
  std::vector<ObjectRow> out;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const auto f = csvFields(line);
    if (static_cast<int>(f.size()) <= std::max({ic, ii, im}))
      throw Error(path + ": line " + std::to_string(n) + ": too few columns");
    fs::path mesh = f[im];
    if (mesh.is_relative()) mesh = base / mesh;
    out.push_back({f[ic], f[ii], mesh.string()});
  }
  if (out.empty()) throw Error(path + ": no objects listed");
  return out;
}

}  // namespace keyturn::rig
