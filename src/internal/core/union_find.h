#pragma once
// Connected sets of points (outlier clusters, border pieces).

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace pcsketch::detail {

/// Union-find with path halving; the root of a set is its smallest index, so the result is deterministic.
struct Clusters {
  std::vector<std::uint32_t> parent;
  explicit Clusters(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace pcsketch::detail
