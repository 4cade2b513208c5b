#pragma once
// A path under the temporary folder for one test: named by the test and this process, so suites
// of two builds running at once on one machine never share (and delete) each other's files.
// Every test's scratch goes through ScratchFolder (tests/structure/scratch_in_one_place.sh): ctest
// gives the tests TMPDIR=BUILD/test-tmp and scratch.tmpdir_left_empty fails on what is left there.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace keyturn::test {

inline std::filesystem::path scratchPath(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("keyturn_" + name + "_" + std::to_string(::getpid()));
}

// scratchPath(NAME), empty at the start and removed with what is in it when the test leaves its
// scope, whether it passed or an ASSERT ended it.
struct ScratchFolder {
  explicit ScratchFolder(const std::string& name) : path(scratchPath(name)) { std::filesystem::remove_all(path); }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  // The folder, made (with its parents) when it is not there yet.
  const std::filesystem::path& made() const {
    std::filesystem::create_directories(path);
    return path;
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path path;
};

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
