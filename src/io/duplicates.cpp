// Exact duplicate points collapsed at load: k-NN of a point repeated m times finds only its copies, and the
// neighbourhood and spacing stages then take time quadratic in m (100,000 copies of one point: minutes).

#include <bit>
#include <cstring>

#include "raw_cloud.h"

namespace pcsketch::io::detail {

namespace {
std::uint64_t hash_position(const Vec3d& p) {
  // +0.0 and -0.0 are the same point: adding 0.0 turns -0.0 into +0.0 before the bits are hashed.
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int d = 0; d < 3; ++d) {
    const auto bits = std::bit_cast<std::uint64_t>(p[d] + 0.0);
    h = (h ^ bits) * 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}
}  // namespace

std::size_t collapse_duplicates(RawCloud& raw) {
  const std::size_t n = raw.positions.size();
  // Indices are 32-bit, as everywhere downstream (the kd-tree refuses larger clouds).
  if (n < 2 || n >= 0xffffffffull) return 0;
  // Open addressing over the kept points (index + 1, 0 = empty), at most half full: expected O(1) per point.
  const std::size_t size = std::bit_ceil(2 * n);
  std::vector<std::uint32_t> table(size, 0);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d p = raw.positions[i];
    std::size_t slot = hash_position(p) & (size - 1);
    bool duplicate = false;
    for (; table[slot] != 0; slot = (slot + 1) & (size - 1))
      if (raw.positions[table[slot] - 1] == p) {
        duplicate = true;
        break;
      }
    if (duplicate) continue;
    // The first copy is kept, with its normal and colour.
    raw.positions[kept] = p;
    if (!raw.normals.empty()) raw.normals[kept] = raw.normals[i];
    if (!raw.colors.empty()) raw.colors[kept] = raw.colors[i];
    for (PointAttribute& a : raw.attributes) a.values[kept] = a.values[i];
    table[slot] = static_cast<std::uint32_t>(kept + 1);
    ++kept;
  }
  raw.positions.resize(kept);
  if (!raw.normals.empty()) raw.normals.resize(kept);
  if (!raw.colors.empty()) raw.colors.resize(kept);
  for (PointAttribute& a : raw.attributes) a.values.resize(kept);
  return n - kept;
}

}  // namespace pcsketch::io::detail
