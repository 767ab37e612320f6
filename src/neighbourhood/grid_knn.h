#pragma once
// Exact k-NN over a uniform grid: of every point of a cloud at once, and of one point or a ball for the kd-tree's
// queries, for the points whose answer the grid can prove.

#include <cstdint>
#include <memory>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"

namespace pcsketch::neighbourhood::detail {

/// A grid over `points` (which must outlive it and not change) with cells of about (k + 1) / 2 points. Every answer
/// equals the kd-tree's bit for bit; where the grid cannot prove one, it says so and the tree is asked.
class GridKnn {
 public:
  GridKnn(const std::vector<Vec3f>& points, std::size_t k);
  ~GridKnn();

  /// Fills row i (k entries at indices + i*k, distances + i*k) with the k nearest points to point i, self excluded
  /// by index, nearest first, ties in index order: the same rows as KdTree::knn_of_point, bit for bit. A row is
  /// filled only when its k-th distance is provably shorter than the way out of the 27 cells around the point's own
  /// (of 125 or 343 cells where the 27 leave few rows), so that no point outside them can belong to the row. The
  /// points left (sparse regions, isolated points, crowded cells) are returned in increasing order, their rows
  /// untouched. Requires k ≥ 1 and points.size() > k.
  std::vector<std::uint32_t> fill(std::size_t k, std::uint32_t* indices, float* distances,
                                  const ProgressFn& progress) const;
  /// KdTree::knn_of_point(i, k), from the smallest cubes of cells around i expected to hold k points; false (the
  /// vectors unspecified) where they do not prove it. Requires k < points.size().
  bool knn_of_point(std::size_t i, std::size_t k, std::vector<std::uint32_t>& indices,
                    std::vector<float>& distances) const;
  /// The points KdTree::radius_unsorted(q, radius) finds, in the grid's order; false (indices unspecified) where the
  /// ball spans too many cells.
  bool within(const Vec3f& q, float radius, std::vector<std::uint32_t>& indices) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcsketch::neighbourhood::detail
