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

// Bounded before the cast (a cell index past int64 is undefined behaviour): a point that far, or a
// side that small, shares the last cell, and the callers' distance checks decide. `offset` (in
// cells) shifts the grid's faces.
inline std::int64_t voxelCell(double coordinate, double inverse_side, double offset = 0.0) {
  const double c = std::floor(coordinate * inverse_side + offset);
  if (!(c > -4.0e18)) return static_cast<std::int64_t>(-4.0e18);  // NaN too
  if (c > 4.0e18) return static_cast<std::int64_t>(4.0e18);
  return static_cast<std::int64_t>(c);
}

}  // namespace keyturn::detail
