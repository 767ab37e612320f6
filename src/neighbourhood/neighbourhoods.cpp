#include "pcsketch/neighbourhood/neighbourhoods.h"

#include <algorithm>

#include "core/parallel_chunks.h"
#include "pcsketch/core/error.h"

namespace pcsketch::neighbourhood {

Neighbourhoods compute_neighbourhoods(const KdTree& tree, const std::vector<Vec3f>& points,
                                      const NeighbourhoodOptions& options) {
  if (tree.size() != points.size())
    throw Error("neighbourhoods: the kd-tree holds " + std::to_string(tree.size()) + " points but the cloud has " +
                std::to_string(points.size()));
  if (options.k > kMaxNeighbours)
    throw Error("neighbourhoods: k = " + std::to_string(options.k) + " exceeds the maximum of " +
                std::to_string(kMaxNeighbours));
  Neighbourhoods result;
  const std::size_t n = points.size();
  result.k = n == 0 ? 0 : std::min(options.k, n - 1);
  const std::size_t k = result.k;
  result.indices.resize(n * k);
  result.distances.resize(n * k);
  if (k == 0) return result;

  detail::parallel_chunks(n, options.progress, "neighbourhoods", [&](std::size_t begin, std::size_t end) {
    thread_local std::vector<std::uint32_t> found;
    thread_local std::vector<float> found_distances;
    for (std::size_t i = begin; i < end; ++i) {
      tree.knn_of_point(i, k, found, found_distances);
      std::copy(found.begin(), found.end(), result.indices.begin() + i * k);
      std::copy(found_distances.begin(), found_distances.end(), result.distances.begin() + i * k);
    }
  });
  return result;
}

}  // namespace pcsketch::neighbourhood
