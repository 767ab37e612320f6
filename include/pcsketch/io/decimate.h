#pragma once
// Deterministic voxel thinning: one point per cell of a regular grid, for clouds bigger than the drawing needs.

#include <cstddef>
#include <optional>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::io {

struct DecimateOptions {
  /// Edge of the voxel grid's cells, in model units; none: no thinning by size.
  std::optional<double> voxel;
  /// Thin to at most this many points (at least 8), with the smallest cell that gets there (found by bisection, to
  /// 0.1 %); none: no limit.
  /// With `voxel` too, the larger of the two cells is used.
  std::optional<std::size_t> max_points;
  bool active() const { return voxel.has_value() || max_points.has_value(); }
};

/// What the thinning did.
struct DecimateReport {
  std::size_t points_before = 0;
  std::size_t points_after = 0;
  double cell = 0;     ///< the cell edge used, model units (0: the cloud was already small enough)
  double seconds = 0;  ///< time taken
};

/// Keeps one point per occupied cell of a grid of cubes of edge `cell` anchored at the bounding box's minimum: the
/// point nearest the cell's centre (ties: the smallest position, x then y then z). Survivors keep their order; every
/// per-point array of the cloud follows. The same points survive for any order of the input.
/// @throws pcsketch::Error if the options ask for a cell <= 0 or max_points < 8.
DecimateReport decimate(PointCloud& cloud, const DecimateOptions& options);

}  // namespace pcsketch::io
