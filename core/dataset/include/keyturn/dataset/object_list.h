#pragma once
// The object list of a simulated dataset (data/objects/objects.csv): class,
// instance and mesh columns; mesh paths are relative to the list.
#include <map>
#include <string>
#include <vector>

namespace keyturn::dataset {

struct ObjectRow {
  std::string cls, instance, mesh;
};

// Throws keyturn::Error naming the file and line for a missing column or file.
std::vector<ObjectRow> readObjectList(const std::string& path);

// The class of each instance in a list with class and instance columns (other columns ignored, so
// an object list reads too): e.g. the categories of BigBIRD's objects (keyturn import bigbird
// --categories). Throws keyturn::Error naming the file for a missing column or an instance in two classes.
std::map<std::string, std::string> readInstanceClasses(const std::string& path);

}  // namespace keyturn::dataset
