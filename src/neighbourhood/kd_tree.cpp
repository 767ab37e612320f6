#include "pcsketch/neighbourhood/kd_tree.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <nanoflann.hpp>

#include "core/ordered_key.h"
#include "grid_knn.h"
#include "pcsketch/core/error.h"

namespace pcsketch::neighbourhood {

namespace {

/// nanoflann dataset adaptor over the caller's positions (no copy).
struct PointsAdaptor {
  const std::vector<Vec3f>& points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][static_cast<Eigen::Index>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointsAdaptor>, PointsAdaptor, 3,
                                                  std::uint32_t>;

/// A bound slightly above `dist_sq`: nanoflann offers only candidates strictly closer than worstDist() and prunes
/// with incrementally rounded box distances, so a point at exactly the bound could otherwise be skipped.
float widened(float dist_sq) { return dist_sq * (1.f + 1e-6f) + std::numeric_limits<float>::denorm_min(); }

/// (squared distance, index) as one ordered key (NaN distances are never offered, nanoflann testing
/// dist < worstDist() first): ties come out in index order whatever the traversal order.
using Candidate = std::uint64_t;
using pcsketch::detail::key_index;
using pcsketch::detail::key_value;
using pcsketch::detail::ordered_key;

/// The k smallest candidates, kept sorted by insertion (fast for small k). worstDist() is widened so that a
/// candidate tied with the current worst is still offered and may win on its index.
class SortedKnn {
 public:
  SortedKnn(std::size_t capacity, Candidate* out) : capacity_(capacity), out_(out) {}
  bool full() const { return count_ == capacity_; }
  float worstDist() const { return worst_; }
  bool addPoint(float dist, std::uint32_t index) {
    const Candidate c = ordered_key(dist, index);
    if (full() && c >= out_[capacity_ - 1]) return true;
    std::size_t m = count_ < capacity_ ? count_++ : capacity_ - 1;
    for (; m > 0 && c < out_[m - 1]; --m) out_[m] = out_[m - 1];
    out_[m] = c;
    if (full()) worst_ = widened(key_value(out_[capacity_ - 1]));
    return true;
  }
  void finish() {}

 private:
  std::size_t capacity_;
  std::size_t count_ = 0;
  Candidate* out_;
  float worst_ = std::numeric_limits<float>::infinity();
};

/// The k smallest candidates in a max-heap, sorted at the end (for large k, where insertion is O(k)).
class HeapKnn {
 public:
  HeapKnn(std::size_t capacity, Candidate* out) : capacity_(capacity), out_(out) {}
  bool full() const { return count_ == capacity_; }
  float worstDist() const { return worst_; }
  bool addPoint(float dist, std::uint32_t index) {
    const Candidate c = ordered_key(dist, index);
    if (!full()) {
      out_[count_++] = c;
      std::push_heap(out_, out_ + count_);
    } else if (c < out_[0]) {
      sift_down(c);
    } else {
      return true;
    }
    if (full()) worst_ = widened(key_value(out_[0]));
    return true;
  }
  void finish() { std::sort(out_, out_ + count_); }

 private:
  /// Replaces the root by `c` and restores the max-heap: one pass down instead of pop_heap + push_heap.
  void sift_down(Candidate c) {
    std::size_t m = 0;
    for (std::size_t child = 1; child < count_; child = 2 * m + 1) {
      if (child + 1 < count_ && out_[child] < out_[child + 1]) ++child;
      if (!(c < out_[child])) break;
      out_[m] = out_[child];
      m = child;
    }
    out_[m] = c;
  }

  std::size_t capacity_;
  std::size_t count_ = 0;
  Candidate* out_;
  float worst_ = std::numeric_limits<float>::infinity();
};

/// Every point at true distance ≤ radius (inclusive, unlike nanoflann's RadiusResultSet; compared after the square
/// root so that the reported distance and the test agree exactly).
class InclusiveRadius {
 public:
  InclusiveRadius(float radius, std::vector<std::pair<std::uint32_t, float>>& hits)
      : radius_(radius), bound_(widened(radius * radius)), hits_(hits) {}
  bool full() const { return true; }
  std::size_t size() const { return hits_.size(); }
  float worstDist() const { return bound_; }
  bool addPoint(float dist, std::uint32_t index) {
    if (std::sqrt(dist) <= radius_) hits_.emplace_back(index, dist);
    return true;
  }

 private:
  float radius_;
  float bound_;
  std::vector<std::pair<std::uint32_t, float>>& hits_;
};

}  // namespace

struct KdTree::Impl {
  PointsAdaptor adaptor;
  // Leaves of 16 points: measured faster than nanoflann's default 10 for k = 16 queries on 1M points.
  Index index;
  std::once_flag built;
  std::unique_ptr<detail::GridKnn> grid;  ///< made by knn_of_every_point

  explicit Impl(const std::vector<Vec3f>& points)
      : adaptor{points},
        index(3, adaptor,
              nanoflann::KDTreeSingleIndexAdaptorParams(
                  16, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex)) {}

  /// The index, built by the first query (the build was 4% of a 1M draw, whose clean cloud may ask none).
  const Index& ready() {
    std::call_once(built, [this] { index.buildIndex(); });
    return index;
  }
};

KdTree::KdTree(const std::vector<Vec3f>& points) {
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw Error("kd-tree: " + std::to_string(points.size()) + " points exceed the 32-bit index limit");
  impl_ = std::make_unique<Impl>(points);
}
KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

std::size_t KdTree::size() const { return impl_->adaptor.points.size(); }

void KdTree::build() const { impl_->ready(); }

void KdTree::knn(const Vec3f& query, std::size_t k, std::vector<std::uint32_t>& indices,
                 std::vector<float>& distances) const {
  k = std::min(k, size());
  indices.resize(k);
  distances.resize(k);
  if (k == 0) return;
  thread_local std::vector<Candidate> found;
  found.resize(k);
  const auto search = [&](auto result) {
    impl_->ready().findNeighbors(result, query.data(), nanoflann::SearchParams());
    result.finish();
  };
  if (k <= 32) {
    search(SortedKnn(k, found.data()));
  } else {
    search(HeapKnn(k, found.data()));
  }
  for (std::size_t m = 0; m < k; ++m) {
    distances[m] = std::sqrt(key_value(found[m]));
    indices[m] = key_index(found[m]);
  }
}

void KdTree::knn_of_point(std::size_t i, std::size_t k, std::vector<std::uint32_t>& indices,
                          std::vector<float>& distances) const {
  if (i >= size()) throw Error("kd-tree: point " + std::to_string(i) + " out of range");
  k = std::min(k, size() - 1);
  if (!impl_->grid || !impl_->grid->knn_of_point(i, k, indices, distances)) tree_knn_of_point(i, k, indices, distances);
}

void KdTree::tree_knn_of_point(std::size_t i, std::size_t k, std::vector<std::uint32_t>& indices,
                               std::vector<float>& distances) const {
  knn(impl_->adaptor.points[i], k + 1, indices, distances);
  // With more than k duplicates of i, i itself may lie beyond the k+1 found: then the farthest one is dropped.
  auto self = std::find(indices.begin(), indices.end(), static_cast<std::uint32_t>(i));
  if (self == indices.end()) self = indices.end() - 1;
  distances.erase(distances.begin() + (self - indices.begin()));
  indices.erase(self);
}

/// (index, squared distance) of every point within `radius` of `query`, in the tree's order.
std::vector<std::pair<std::uint32_t, float>>& KdTree::within(const Vec3f& query, float radius) const {
  thread_local std::vector<std::pair<std::uint32_t, float>> hits;
  hits.clear();
  if (!(radius >= 0) || size() == 0) return hits;
  InclusiveRadius result(radius, hits);
  impl_->ready().findNeighbors(result, query.data(), nanoflann::SearchParams());
  return hits;
}

void KdTree::radius_unsorted(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices) const {
  indices.clear();
  for (const auto& hit : within(query, radius)) indices.push_back(hit.first);
}

void KdTree::radius_any_order(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices) const {
  if (!impl_->grid || !impl_->grid->within(query, radius, indices)) radius_unsorted(query, radius, indices);
}

void KdTree::knn_of_every_point(std::size_t k, std::uint32_t* indices, float* distances,
                                const ProgressFn& progress) const {
  // The grid's fill has already failed on the rows it leaves: the tree answers them.
  make_grid(k);
  fill_rows(impl_->grid->fill(k, indices, distances, progress), k, indices, distances, false);
}

void KdTree::knn_of_rows(const std::vector<std::uint32_t>& rows, std::size_t k, std::uint32_t* indices,
                         float* distances) const {
  make_grid(k);
  fill_rows(rows, k, indices, distances, true);
}

void KdTree::make_grid(std::size_t k) const {
  if (k == 0 || k >= size())
    throw Error("kd-tree: " + std::to_string(k) + " neighbours of each of " + std::to_string(size()) + " points");
  if (!impl_->grid) impl_->grid = std::make_unique<detail::GridKnn>(impl_->adaptor.points, k);
}

void KdTree::fill_rows(const std::vector<std::uint32_t>& rows, std::size_t k, std::uint32_t* indices,
                       float* distances, bool grid_first) const {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 64), [&](const auto& r) {
    thread_local std::vector<std::uint32_t> found;
    thread_local std::vector<float> found_distances;
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      if (grid_first) knn_of_point(rows[c], k, found, found_distances);
      else tree_knn_of_point(rows[c], k, found, found_distances);
      std::copy(found.begin(), found.end(), indices + rows[c] * k);
      std::copy(found_distances.begin(), found_distances.end(), distances + rows[c] * k);
    }
  });
}

void KdTree::radius(const Vec3f& query, float radius, std::vector<std::uint32_t>& indices,
                    std::vector<float>& distances) const {
  indices.clear();
  distances.clear();
  std::vector<std::pair<std::uint32_t, float>>& hits = within(query, radius);
  std::sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) {
    return a.second < b.second || (a.second == b.second && a.first < b.first);
  });
  indices.reserve(hits.size());
  distances.reserve(hits.size());
  for (const auto& [i, d] : hits) {
    indices.push_back(i);
    distances.push_back(std::sqrt(d));
  }
}

}  // namespace pcsketch::neighbourhood
