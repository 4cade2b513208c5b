#pragma once
// FNV-1a, 64 bits: a hash that is the same in every build and on every machine, for
// names of files (the feature cache) and checks across processes (evaluate's parts).
#include <cstdint>
#include <string>

namespace keyturn {

// basis: FNV's offset basis, or another start (a seed folded in) for a keyed hash.
inline std::uint64_t fnv1a(const std::string& s, std::uint64_t basis = 1469598103934665603ull) {
  std::uint64_t h = basis;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace keyturn
