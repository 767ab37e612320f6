#include "pcsketch/neighbourhood/neighbourhoods.h"

#include <tbb/parallel_invoke.h>

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
  // 64 MB each at 1M points, zeroed as their pages fault in: the two side by side.
  tbb::parallel_invoke([&] { result.indices.resize(n * result.k); }, [&] { result.distances.resize(n * result.k); });
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

}  // namespace pcsketch::neighbourhood
