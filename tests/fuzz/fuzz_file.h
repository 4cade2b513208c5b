#pragma once
// libFuzzer harness helper: the loaders under test read files, so each input
// is written to a per-process scratch folder with the right name first. The folder goes when the
// harness exits (libFuzzer's exit(0) after its runs); after a crash it stays in tests/fuzz/run.sh's
// work folder (TMPDIR there), with the crash input.
#include <cstdint>
#include <fstream>
#include <string>

#include "support/scratch_path.h"

namespace keyturn::fuzz {

inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
  static const test::ScratchFolder scratch("fuzz");
  const std::string path = (scratch.made() / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                static_cast<std::streamsize>(size));
  return path;
}

}  // namespace keyturn::fuzz
