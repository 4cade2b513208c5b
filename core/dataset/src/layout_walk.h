#pragma once
// The files of another tool's dataset folder, for the import layouts: every regular file below the
// source (hidden files and folders skipped, e.g. keyturn's own .keyturn/), sorted, with its path
// split into folder names and file name.
#include <string>
#include <vector>

namespace keyturn::dataset {

struct LayoutFile {
  std::string path;                // source/…/name
  std::vector<std::string> parts;  // relative to the source: folders…, name
};

// Throws keyturn::Error when the source is not a folder; an unreadable folder is one problem line.
std::vector<LayoutFile> layoutFiles(const std::string& source, std::vector<std::string>& problems);

}  // namespace keyturn::dataset
