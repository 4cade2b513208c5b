#pragma once
// A Netpbm bitmap (.pbm: P4 binary or P1 ascii), as BigBIRD's object masks are stored: one bit a
// pixel, 1 = black. Throws keyturn::Error naming the file when it is not a complete bitmap.
#include <cstdint>
#include <string>
#include <vector>

namespace keyturn::dataset {

struct Bitmap {
  std::vector<std::uint8_t> black;  // row-major, 1 where the pixel is black
  std::uint32_t width = 0, height = 0;
};

Bitmap readPbm(const std::string& path);

}  // namespace keyturn::dataset
