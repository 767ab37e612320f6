#include "pcsketch/neighbourhood/neighbourhoods.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "pcsketch/core/error.h"

namespace pcsketch::neighbourhood {
namespace {

/// Empty lists sized for `points`, k clamped to the cloud; checks k.
Neighbourhoods sized(const std::vector<Vec3f>& points, const NeighbourhoodOptions& options) {
  if (options.k > kMaxNeighbours)
    throw Error("neighbourhoods: k = " + std::to_string(options.k) + " exceeds the maximum of " +
                std::to_string(kMaxNeighbours));
  Neighbourhoods result;
  const std::size_t n = points.size();
  result.k = n == 0 ? 0 : std::min(options.k, n - 1);
  // 64 MB each at 1M points, left unzeroed: the search writes every entry, in parallel.
  result.indices.resize(n * result.k);
  result.distances.resize(n * result.k);
  return result;
}

}  // namespace

Neighbourhoods compute_neighbourhoods(const KdTree& tree, const std::vector<Vec3f>& points,
                                      const NeighbourhoodOptions& options) {
  if (tree.size() != points.size())
    throw Error("neighbourhoods: the kd-tree holds " + std::to_string(tree.size()) + " points but the cloud has " +
                std::to_string(points.size()));
  Neighbourhoods result = sized(points, options);
  if (result.k > 0) tree.knn_of_every_point(result.k, result.indices.data(), result.distances.data(), options.progress);
  return result;
}

Neighbourhoods index_neighbourhoods(const std::vector<Vec3f>& points, std::optional<KdTree>& tree,
                                    const NeighbourhoodOptions& options) {
  // The tree is built by its first query: here only if the grid leaves rows.
  tree.emplace(points);
  return compute_neighbourhoods(*tree, points, options);
}

Neighbourhoods neighbourhoods_after_removal(const Neighbourhoods& before, const std::vector<std::uint8_t>& removed,
                                           const std::vector<Vec3f>& points, std::optional<KdTree>& tree,
                                           const NeighbourhoodOptions& options) {
  const std::size_t old_n = removed.size();
  const auto left = static_cast<std::size_t>(std::count(removed.begin(), removed.end(), 0));
  if (before.size() != old_n || left != points.size())
    throw Error("neighbourhoods: " + std::to_string(removed.size()) + " removal flags for " +
                std::to_string(before.size()) + " lists and " + std::to_string(points.size()) + " points left");
  Neighbourhoods result = sized(points, options);
  const std::size_t k = result.k;
  if (k == 0 || k != before.k) return index_neighbourhoods(points, tree, options);
  std::vector<std::uint32_t> renumbered(old_n, UINT32_MAX), old_of(points.size());
  for (std::uint32_t i = 0, next = 0; i < old_n; ++i)
    if (!removed[i]) old_of[next] = i, renumbered[i] = next++;
  std::vector<std::uint8_t> changed(points.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t from = old_of[i];
      for (std::size_t m = 0; m < k; ++m) {
        const std::uint32_t j = renumbered[before.indices[from * k + m]];
        changed[i] |= j == UINT32_MAX;
        result.indices[i * k + m] = j;
        result.distances[i * k + m] = before.distances[from * k + m];
      }
    }
  });
  std::vector<std::uint32_t> rows;
  for (std::uint32_t i = 0; i < changed.size(); ++i)
    if (changed[i]) rows.push_back(i);
  tree.emplace(points);
  tree->knn_of_rows(rows, k, result.indices.data(), result.distances.data());
  return result;
}

}  // namespace pcsketch::neighbourhood
