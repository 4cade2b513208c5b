#pragma once
// One 64-bit key per voxel (21 bits per axis, offset to ±1M cells: far beyond any view at
// millimetre spacing), for the hash grids of the working resolution, the radius table and the
// cluster step. Internal to keyturn_core.
#include <cmath>
#include <cstdint>

namespace keyturn::detail {

inline std::uint64_t voxelKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  return (static_cast<std::uint64_t>(x + (1 << 20)) & 0x1FFFFF) |
         (static_cast<std::uint64_t>(y + (1 << 20)) & 0x1FFFFF) << 21 |
         (static_cast<std::uint64_t>(z + (1 << 20)) & 0x1FFFFF) << 42;
}

inline std::int64_t voxelCell(float coordinate, double inverse_side) {
  return static_cast<std::int64_t>(std::floor(coordinate * inverse_side));
}

}  // namespace keyturn::detail
