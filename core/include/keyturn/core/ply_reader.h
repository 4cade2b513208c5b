#pragma once
// keyturn's own PLY reader: ascii and binary (little and big endian), scalar
// and list properties, every count and index checked against the bytes that
// are really there. It replaces PCL's reader, which crashed on fuzzed files
// (docs/reliability.md). Unknown elements are read past and kept.
#include <cstddef>
#include <string>
#include <vector>

namespace keyturn {

struct PlyProperty {
  std::string name;
  bool is_list = false;
  std::string count_type;  // lists only
  std::string value_type;
  // Scalars: one value per element item. Lists: the values of every item
  // back to back, item i at [offsets[i], offsets[i + 1]).
  std::vector<double> values;
  std::vector<std::size_t> offsets;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
  const PlyProperty* find(const std::string& name) const;
};

struct PlyData {
  std::string format;  // ascii | binary_little_endian | binary_big_endian
  std::vector<PlyElement> elements;
  std::vector<std::string> obj_info;  // the text after each "obj_info"
  const PlyElement* find(const std::string& name) const;
};

// Throws keyturn::Error "<path>: <what was wrong>" for any malformed input.
PlyData readPly(const std::string& path);

}  // namespace keyturn
