#pragma once
// The object list of a simulated dataset (data/objects/objects.csv): class,
// instance and mesh columns; mesh paths are relative to the list.
#include <string>
#include <vector>

namespace keyturn::rig {

struct ObjectRow {
  std::string cls, instance, mesh;
};

// Throws keyturn::Error naming the file and line for a missing column or file.
std::vector<ObjectRow> readObjectList(const std::string& path);

}  // namespace keyturn::rig
