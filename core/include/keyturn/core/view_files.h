#pragma once
// Expanding the FILES_OR_FOLDERS arguments of a command into view files.
#include <string>
#include <vector>

namespace keyturn {

struct ViewFileList {
  std::vector<std::string> files;   // in argument order, folders sorted
  std::vector<std::string> errors;  // one line per argument that could not be used
};

// Folders contribute every .pcd/.ply below them (recursively, sorted).
ViewFileList collectViewFiles(const std::vector<std::string>& inputs);

}  // namespace keyturn
