#pragma once
// libFuzzer harness helper: the loaders under test read files, so each input
// is written to a per-process temporary file with the right name first.
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>

namespace keyturn::fuzz {

inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string dir = "/tmp/keyturn_fuzz_" + std::to_string(::getpid());
  ::mkdir(dir.c_str(), 0700);
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                static_cast<std::streamsize>(size));
  return path;
}

}  // namespace keyturn::fuzz
