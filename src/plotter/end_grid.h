#pragma once
// Private to plotter/: stroke ends in a uniform grid, for the nearest-end queries of merging and sorting.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::plotter {

/// Pen positions in image pixels, in double: travel sums over thousands of strokes.
using Vec2d = Eigen::Vector2d;

namespace detail {

/// Points (stroke ends) in a uniform grid of about one point a cell, removable one by one. Queries search rings of
/// cells outward and stop once no unsearched cell can hold a nearer point; the grid is rebuilt, with larger cells,
/// when three quarters of its points are gone, so the late queries of a greedy sort do not scan empty cells.
class EndGrid {
 public:
  static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();

  /// Every point alive; ids are indices in `points`, which must be finite.
  explicit EndGrid(std::vector<Vec2d> points);
  /// Marks point `id` gone (no effect if it already is).
  void remove(std::size_t id);
  /// The alive point nearest to q within `max_distance` (inclusive), ties to the smaller id; npos if none.
  std::size_t nearest(const Vec2d& q, double max_distance = std::numeric_limits<double>::infinity()) const;

 private:
  void rebuild();
  /// The cell holding coordinate x along one axis, unclamped (a query may lie outside the grid).
  long cell_of(double x, double lo) const;

  std::vector<Vec2d> points_;
  std::vector<std::uint8_t> alive_;
  std::size_t alive_count_ = 0, built_count_ = 0;
  Vec2d lo_ = Vec2d::Zero();
  double cell_ = 1;
  long nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_, ids_;  ///< CSR: the points of cell c are ids_[start_[c] .. start_[c + 1])
};

}  // namespace detail
}  // namespace pcsketch::plotter
