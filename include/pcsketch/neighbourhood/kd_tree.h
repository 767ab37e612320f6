#pragma once
// k-nearest and radius queries over 3D points (nanoflann behind a PImpl).

#include <cstdint>
#include <memory>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"

namespace pcsketch::neighbourhood {

/// A kd-tree over `points`, which must outlive it and not change. Built once, by the first query (the build is
/// serial, and a clean cloud's draw asks the tree nothing); every const query is thread-safe (nanoflann's contract;
/// queries that come during the build wait for it). Radii and distances are true distances, not squared.
class KdTree {
 public:
  explicit KdTree(const std::vector<Vec3f>& points);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  /// The k nearest points to `query` (fewer if the tree holds fewer), nearest first; ties in index order.
  void knn(const Vec3f& query, std::size_t k, std::vector<std::uint32_t>& indices, std::vector<float>& distances) const;
  /// The indices of all points within `radius` of `query`, in no particular order (no sorting: for callers that
  /// select among them themselves). The order is the tree's, the same from run to run.
  void radius_unsorted(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices) const;
  /// The points radius_unsorted finds, in an order that may differ from its: from the grid of knn_of_every_point
  /// where it has been made and proves the ball. For callers that need the set only (a nearest, a count).
  void radius_any_order(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices) const;
  /// All points within `radius` of `query`, nearest first.
  void radius(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices,
              std::vector<float>& distances) const;
  /// The k nearest neighbours of the tree's own point i, nearest first, ties in index order, i itself excluded by
  /// index (its duplicates at distance 0 are genuine neighbours). Fewer than k if the tree holds ≤ k points. After
  /// knn_of_every_point, its grid answers first where it proves the answer.
  void knn_of_point(std::size_t i, std::size_t k, std::vector<std::uint32_t>& indices,
                    std::vector<float>& distances) const;
  /// knn_of_point(i, k) of every point i into indices + i·k and distances + i·k (k < size()), in parallel: from a
  /// uniform grid of the points where it proves the row (most rows), from the tree elsewhere. The grid, of cells of
  /// about (k + 1) / 2 points, stays with the tree for its later single-point queries. Not concurrently with other
  /// queries.
  void knn_of_every_point(std::size_t k, std::uint32_t* indices, float* distances, const ProgressFn& progress) const;
  /// knn_of_point(i, k) of each i of `rows` into indices + i·k and distances + i·k, in parallel, with the grid of
  /// knn_of_every_point (made here if there is none yet, so that later queries find it too). Not concurrently with
  /// other queries.
  void knn_of_rows(const std::vector<std::uint32_t>& rows, std::size_t k, std::uint32_t* indices,
                   float* distances) const;
  std::size_t size() const;
  /// Builds the tree now if it is not built yet (a query would): for a caller with a core to spare before queries.
  void build() const;

 private:
  /// (index, squared distance) of the points within `radius`, unsorted, in a per-thread buffer.
  std::vector<std::pair<std::uint32_t, float>>& within(const Vec3f& query, float radius) const;
  /// knn_of_point from the tree alone.
  void tree_knn_of_point(std::size_t i, std::size_t k, std::vector<std::uint32_t>& indices,
                         std::vector<float>& distances) const;
  /// Makes the grid of knn_of_every_point for rows of k neighbours if there is none yet; checks 0 < k < size().
  void make_grid(std::size_t k) const;
  /// Rows `rows` of knn_of_every_point's output, from knn_of_point (`grid_first`) or from the tree alone.
  void fill_rows(const std::vector<std::uint32_t>& rows, std::size_t k, std::uint32_t* indices, float* distances,
                 bool grid_first) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcsketch::neighbourhood
