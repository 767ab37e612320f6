#include "pcsketch/neighbourhood/neighbourhoods.h"

#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include <algorithm>

#include "core/parallel_chunks.h"
#include "grid_knn.h"
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

/// The rows of `rest` from the tree.
void fill_from_tree(const KdTree& tree, const std::vector<std::uint32_t>& rest, Neighbourhoods& result) {
  const std::size_t k = result.k;
  pcsketch::detail::parallel_chunks(
      rest.size(), {}, "neighbourhoods",
      [&](std::size_t begin, std::size_t end) {
        thread_local std::vector<std::uint32_t> found;
        thread_local std::vector<float> found_distances;
        for (std::size_t r = begin; r < end; ++r) {
          const std::size_t i = rest[r];
          tree.knn_of_point(i, k, found, found_distances);
          std::copy(found.begin(), found.end(), result.indices.begin() + std::ptrdiff_t(i * k));
          std::copy(found_distances.begin(), found_distances.end(), result.distances.begin() + std::ptrdiff_t(i * k));
        }
      },
      64);
}

}  // namespace

Neighbourhoods compute_neighbourhoods(const KdTree& tree, const std::vector<Vec3f>& points,
                                      const NeighbourhoodOptions& options) {
  if (tree.size() != points.size())
    throw Error("neighbourhoods: the kd-tree holds " + std::to_string(tree.size()) + " points but the cloud has " +
                std::to_string(points.size()));
  Neighbourhoods result = sized(points, options);
  if (result.k == 0) return result;
  const std::vector<std::uint32_t> rest =
      detail::grid_knn(points, result.k, result.indices.data(), result.distances.data(), options.progress);
  fill_from_tree(tree, rest, result);
  return result;
}

Neighbourhoods index_neighbourhoods(const std::vector<Vec3f>& points, std::optional<KdTree>& tree,
                                    const NeighbourhoodOptions& options) {
  Neighbourhoods result = sized(points, options);
  // The tree's build is serial: it runs beside the grid search, which takes the other cores.
  tbb::task_group build;
  build.run([&] { tree.emplace(points); });
  std::vector<std::uint32_t> rest;
  try {
    if (result.k > 0)
      rest = detail::grid_knn(points, result.k, result.indices.data(), result.distances.data(), options.progress);
  } catch (...) {
    build.wait();
    throw;
  }
  build.wait();
  fill_from_tree(*tree, rest, result);
  return result;
}

}  // namespace pcsketch::neighbourhood
