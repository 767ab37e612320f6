#pragma once
// Morton (Z-order) codes of integer cell coordinates: near cells get near codes, so sorting by code keeps space
// together in memory.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::neighbourhood::detail {

/// Bits per axis of a code: three axes fill 63 bits.
inline constexpr int kMortonBits = 21;
inline constexpr std::uint32_t kMortonMax = (1u << kMortonBits) - 1;

/// Spreads the low 21 bits of v so that two zero bits separate consecutive bits.
inline std::uint64_t spread_bits(std::uint64_t v) {
  v &= kMortonMax;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// The code of cell (x, y, z), each in [0, kMortonMax].
inline std::uint64_t morton(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return spread_bits(x) | spread_bits(y) << 1 | spread_bits(z) << 2;
}

/// The finest cells: 2^21 per axis over the largest side of a box, one cubic grid that keeps the curve isotropic.
/// Float arithmetic, the same for spatial_order and the grid search, so that a cloud in spatial order is sorted.
struct FinestCells {
  Vec3f min;
  float scale;  ///< cells per unit length
  explicit FinestCells(const Box3f& box) : min(box.min) {
    const float side = box.empty() ? 0.f : box.size().maxCoeff();
    scale = side > 0 ? static_cast<float>(kMortonMax) / side : 0.f;
  }
  std::uint64_t code_of(const Vec3f& p) const {
    std::uint32_t cell[3];
    for (int axis = 0; axis < 3; ++axis) {
      const float t = (p[axis] - min[axis]) * scale;
      cell[axis] = static_cast<std::uint32_t>(t >= 0 ? std::min(t, float(kMortonMax)) : 0.f);  // NaN: cell 0
    }
    return morton(cell[0], cell[1], cell[2]);
  }
};

/// A point's code with its index: sorted, cells are runs in Morton order, and the keys are unique (the index breaks
/// ties), so a parallel sort is deterministic.
struct MortonKeyed {
  std::uint64_t code;
  std::uint32_t index;
  bool operator<(const MortonKeyed& o) const { return code < o.code || (code == o.code && index < o.index); }
};

/// Sorts `keyed` (what tbb::parallel_sort would give: the keys are unique), by buckets of the codes' top bits in
/// parallel, then each bucket in cache.
void sort_keyed(std::vector<MortonKeyed>& keyed);

}  // namespace pcsketch::neighbourhood::detail
