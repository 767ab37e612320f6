#pragma once
// A (value, index) pair packed in one word so that one unsigned compare orders pairs lexicographically: the k-NN
// result sets, the grid's and the curvature fits' neighbour selections and the angular sort all rank by it, with
// ties coming out in index order whatever the order they were met in.

#include <bit>
#include <cstdint>

namespace pcsketch::detail {

/// `value` must not be negative (squared distances, pseudo-angles): non-negative floats order like their bits. NaN
/// values are the caller's to keep out.
inline std::uint64_t ordered_key(float value, std::uint32_t index) {
  return std::uint64_t{std::bit_cast<std::uint32_t>(value)} << 32 | index;
}
inline float key_value(std::uint64_t key) { return std::bit_cast<float>(static_cast<std::uint32_t>(key >> 32)); }
inline std::uint32_t key_index(std::uint64_t key) { return static_cast<std::uint32_t>(key); }

}  // namespace pcsketch::detail
