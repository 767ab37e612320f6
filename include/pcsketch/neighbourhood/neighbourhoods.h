#pragma once
// The k nearest neighbours of every point, computed once, stored flat, shared by every later stage.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pcsketch/core/buffer.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/kd_tree.h"

namespace pcsketch::neighbourhood {

/// Most neighbours per point any stage asks for: memory is 8 bytes per neighbour and point, and a k near the point
/// count would make the lists quadratic (k = 10^6 on 10k points took 772 MB).
inline constexpr std::size_t kMaxNeighbours = 256;

struct NeighbourhoodOptions {
  /// Neighbours per point, the point itself excluded. 16 is enough for stable PCA normals and a quadric fit
  /// (6 unknowns) on scanned data while keeping memory at 128 bytes a point. At most kMaxNeighbours.
  std::size_t k = 16;
  ProgressFn progress;  ///< optional
};

/// Flat k-NN lists: neighbours of point i are indices[i*k .. i*k+k), nearest first, self excluded.
/// A cloud with fewer than k+1 points has k = size-1.
struct Neighbourhoods {
  std::size_t k = 0;
  Buffer<std::uint32_t> indices;  ///< #P*k (a std::vector that sizes without zeroing: core/buffer.h)
  Buffer<float> distances;        ///< #P*k, true distances, ascending per point

  std::size_t size() const { return k == 0 ? 0 : indices.size() / k; }
  std::span<const std::uint32_t> of(std::size_t i) const { return {indices.data() + i * k, k}; }
  std::span<const float> distances_of(std::size_t i) const { return {distances.data() + i * k, k}; }
};

/// k-NN of every point of the tree (`points` are the tree's points), in parallel; deterministic for any thread count.
/// Ties are broken by index; each point itself is excluded by index, so its duplicates count as neighbours.
/// Most rows come from a uniform grid (each cell's candidates gathered once for all its points); the tree answers the
/// rows the grid cannot prove (sparse regions, isolated points): the lists equal the tree's own, bit for bit.
/// @throws pcsketch::Error if the tree does not hold points.size() points
Neighbourhoods compute_neighbourhoods(const KdTree& tree, const std::vector<Vec3f>& points,
                                      const NeighbourhoodOptions& options = {});

/// As compute_neighbourhoods, with the kd-tree of `points` put into `tree` for callers that need it afterwards (it
/// builds itself at its first query: here only when the grid leaves rows).
Neighbourhoods index_neighbourhoods(const std::vector<Vec3f>& points, std::optional<KdTree>& tree,
                                    const NeighbourhoodOptions& options = {});

/// index_neighbourhoods of `points`: what is left, in order, of the cloud whose lists are `before` once the points
/// flagged in `removed` are taken out. A list that held none of them keeps its neighbours, renumbered (taking points
/// out brings no other nearer, and renumbering in order keeps ties in index order); the others are queried again.
/// The same lists bit for bit, at the cost of the ones that changed (a few stray points no longer cost a second
/// pass over the whole cloud).
/// @throws pcsketch::Error if `removed` does not hold a flag per point of `before` or the counts disagree
Neighbourhoods neighbourhoods_after_removal(const Neighbourhoods& before, const std::vector<std::uint8_t>& removed,
                                           const std::vector<Vec3f>& points, std::optional<KdTree>& tree,
                                           const NeighbourhoodOptions& options = {});

}  // namespace pcsketch::neighbourhood
