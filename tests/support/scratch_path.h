#pragma once
// A path under the temporary folder for one test: named by the test and this process, so suites
// of two builds running at once on one machine never share (and delete) each other's files.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace keyturn::test {

inline std::filesystem::path scratchPath(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("keyturn_" + name + "_" + std::to_string(::getpid()));
}

// TEXT written to PATH (its folders made); returns the path.
inline std::string writeText(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path.string();
}

// The whole text of PATH ("" when it cannot be read).
inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace keyturn::test
