#pragma once
// k-nearest and radius queries over 3D points (nanoflann behind a PImpl).

#include <cstdint>
#include <memory>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::neighbourhood {

/// A kd-tree over `points`, which must outlive it and not change. Built once in the constructor; every const query
/// is thread-safe (nanoflann's contract). Radii and distances are true distances, not squared.
class KdTree {
 public:
  explicit KdTree(const std::vector<Vec3f>& points);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  /// The k nearest points to `query` (fewer if the tree holds fewer), nearest first; ties in index order.
  void knn(const Vec3f& query, std::size_t k, std::vector<std::uint32_t>& indices, std::vector<float>& distances) const;
  /// The indices of all points within `radius` of `query`, in no particular order (no sorting: for callers that
  /// select among them themselves).
  void radius_unsorted(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices) const;
  /// All points within `radius` of `query`, nearest first.
  void radius(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices,
              std::vector<float>& distances) const;
  /// The k nearest neighbours of the tree's own point i, nearest first, ties in index order, i itself excluded by
  /// index (its duplicates at distance 0 are genuine neighbours). Fewer than k if the tree holds ≤ k points.
  void knn_of_point(std::size_t i, std::size_t k, std::vector<std::uint32_t>& indices,
                    std::vector<float>& distances) const;
  std::size_t size() const;

 private:
  /// (index, squared distance) of the points within `radius`, unsorted, in a per-thread buffer.
  std::vector<std::pair<std::uint32_t, float>>& within(const Vec3f& query, float radius) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcsketch::neighbourhood
