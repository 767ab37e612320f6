#pragma once
// A uniform grid over 2D or 3D points for fixed-radius queries (private to the view stage). Dense over the points'
// bounding box, with the cell size enlarged when needed so the cell count stays within a few times the point count.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace pcsketch::view::detail {

template <int D>
class PointGrid {
 public:
  using Vec = Eigen::Matrix<float, D, 1>;

  /// Grid over (a copy of) `points` with cells of at least `cell` units.
  PointGrid(std::span<const Vec> points, float cell) {
    lo_ = Vec::Constant(0.f);
    Vec hi = Vec::Constant(0.f);
    if (!points.empty()) {
      lo_ = points[0];
      hi = points[0];
      for (const Vec& p : points) {
        lo_ = lo_.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
    const Vec extent = (hi - lo_).cwiseMax(Vec::Constant(1e-6f));
    // A NaN or non-positive cell (a radius factor of nan) would never stop the loop below: one cell spans the cloud.
    cell_ = cell > 0.f && std::isfinite(cell) ? std::max(cell, 1e-6f * extent.maxCoeff()) : extent.maxCoeff();
    // Cap the cell count at about 4 per point (plus a constant): enlarge cells until it fits.
    const double budget = 4.0 * static_cast<double>(points.size()) + 64.0;
    for (;;) {
      double cells = 1;
      for (int d = 0; d < D; ++d) cells *= std::floor(extent[d] / cell_) + 1;
      if (cells <= budget) break;
      cell_ *= 1.5f;
    }
    std::size_t total = 1;
    for (int d = 0; d < D; ++d) {
      dims_[d] = static_cast<std::int64_t>(std::floor(extent[d] / cell_)) + 1;
      total *= static_cast<std::size_t>(dims_[d]);
    }
    // Counting sort of the points by cell.
    start_.assign(total + 1, 0);
    // The cells in parallel (a division per coordinate), the counts and places serially.
    std::vector<std::uint32_t> cell_of(points.size());
    in_parallel(points.size(),
                [&](std::size_t i) { cell_of[i] = static_cast<std::uint32_t>(linear(coords(points[i]))); });
    for (const std::uint32_t c : cell_of) ++start_[c + 1];
    for (std::size_t c = 0; c < total; ++c) start_[c + 1] += start_[c];
    order_.resize(points.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i) order_[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
    // A copy in cell order: a query then scans contiguous memory instead of chasing indices.
    sorted_.resize(points.size());
    in_parallel(points.size(), [&](std::size_t k) { sorted_[k] = points[order_[k]]; });
  }

  /// Point indices in cell order: iterating queries in this order keeps the scanned cells in cache.
  const std::vector<std::uint32_t>& order() const { return order_; }

  float cell() const { return cell_; }

  /// Calls f(index, squared distance) for every point within `radius` of q, in grid order (deterministic).
  template <class F>
  void for_each_within(const Vec& q, float radius, F&& f) const {
    for_each_within_until(q, radius, [&](std::uint32_t i, float d2) {
      f(i, d2);
      return true;
    });
  }

  /// As for_each_within, stopping as soon as f returns false. Returns whether the scan ran to the end.
  template <class F>
  bool for_each_within_until(const Vec& q, float radius, F&& f) const {
    return scan(q, radius, f, false);
  }

  /// As for_each_within_until, but q's own cell first: where f stops once points lie all around q (the outline
  /// test), they are found sooner. The same points in another order: a scan that runs to the end sees them all.
  template <class F>
  bool for_each_within_until_centre_first(const Vec& q, float radius, F&& f) const {
    return scan(q, radius, f, true);
  }

 private:
  template <class F>
  bool scan(const Vec& q, float radius, F& f, bool centre_first) const {
    if (sorted_.empty()) return true;
    const float r2 = radius * radius;
    Eigen::Matrix<std::int64_t, D, 1> a, b;
    for (int d = 0; d < D; ++d) {
      a[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((q[d] - radius - lo_[d]) / cell_)), 0,
                                      dims_[d] - 1);
      b[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((q[d] + radius - lo_[d]) / cell_)), 0,
                                      dims_[d] - 1);
      if (q[d] + radius < lo_[d] || q[d] - radius > lo_[d] + cell_ * static_cast<float>(dims_[d])) return true;
    }
    const auto scan_cell = [&](std::size_t cell) {
      for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
        const float d2 = (sorted_[k] - q).squaredNorm();
        if (d2 <= r2 && !f(order_[k], d2)) return false;
      }
      return true;
    };
    // q's cell lies between a and b: the floors are monotone (truncation and floor agree once clamped at 0).
    const std::size_t centre = centre_first ? linear(coords(q)) : total_cells();
    if (centre_first && !scan_cell(centre)) return false;
    Eigen::Matrix<std::int64_t, D, 1> c = a;
    for (;;) {
      const std::size_t cell = linear(c);
      if (cell != centre && !scan_cell(cell)) return false;
      int d = 0;
      while (d < D && ++c[d] > b[d]) {
        c[d] = a[d];
        ++d;
      }
      if (d == D) return true;
    }
  }

  /// Calls f(i) for every i in [0, n), in parallel; f writes only slot i.
  template <class F>
  static void in_parallel(std::size_t n, const F& f) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
    });
  }

  std::size_t total_cells() const { return start_.size() - 1; }
  Eigen::Matrix<std::int64_t, D, 1> coords(const Vec& p) const {
    Eigen::Matrix<std::int64_t, D, 1> c;
    for (int d = 0; d < D; ++d)
      c[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>((p[d] - lo_[d]) / cell_), 0, dims_[d] - 1);
    return c;
  }
  std::size_t linear(const Eigen::Matrix<std::int64_t, D, 1>& c) const {
    std::size_t index = 0;
    for (int d = D - 1; d >= 0; --d) index = index * static_cast<std::size_t>(dims_[d]) + static_cast<std::size_t>(c[d]);
    return index;
  }

  Vec lo_;
  float cell_ = 1.f;
  std::int64_t dims_[D]{};
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> order_;
  std::vector<Vec> sorted_;
};

}  // namespace pcsketch::view::detail
