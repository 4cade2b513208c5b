#pragma once
// Writes a file so that a crash leaves either the old or the new content:
// temporary name, fsync, rename. Throws keyturn::Error naming the path.
#include <string>

namespace keyturn::learning {

void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace keyturn::learning
