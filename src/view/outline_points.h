#pragma once
// The outline test of contour extraction (paper §IV.B): which projected points are boundary points of the 2D point
// set, i.e. lie on the outline (silhouette) of the view, and which way the empty side lies from each.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/view/contours.h"

namespace pcsketch::view::detail {

/// The outline's boundary points, as ContourPoints holds them.
struct OutlinePoints {
  std::vector<std::uint32_t> boundary;  ///< #B: indices of the boundary points, ascending
  std::vector<Vec2f> outward;           ///< #B: unit image direction of each boundary point's largest empty gap
};

/// Finds the outline's boundary points among the projected points.
/// @param projected #P: (u, v, depth) of every point
/// @param spacing_px #P: each point's spacing unit in pixels; 0 leaves the point out (behind a perspective eye)
/// @param neighbourhoods the cloud's 3D k-NN lists, or empty: with them most interior points are settled without a
///   2D query (when gap_threshold_deg ≥ 90°); `border` needs them
/// @param border empty or #P: the rims of an open scan; points of a rim that is not drawn (2) and their nearest
///   interior_neighbours are no boundary points (see find_contour_points)
/// @param o reads radius_factor, k, gap_threshold_deg, quadrant_test, confirm_factor, confirm_half_angle_deg,
///   interior_neighbours and progress ("contour points")
OutlinePoints find_outline_points(const std::vector<Vec3f>& projected, const std::vector<float>& spacing_px,
                                  const neighbourhood::Neighbourhoods& neighbourhoods,
                                  const std::vector<std::uint8_t>& border, const ContourOptions& o);

}  // namespace pcsketch::view::detail
