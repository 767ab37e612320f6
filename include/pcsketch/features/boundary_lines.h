#pragma once
// The border of an open scan (a façade, a terrain, a half-scanned statue): the points where the surface ends, chained
// into lines of kind Boundary. Beyond the paper, whose clouds are closed. Small holes (a gap of the sampling, a spot
// the scanner missed) are found too, so that no stage draws them, but they make no line.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/features/join_lines.h"
#include "pcsketch/features/trace_lines.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::features {

struct BoundaryOptions {
  /// Find borders at all. Off: no point is a border point and no boundary line is drawn; hole rims may then be
  /// drawn as outline where they are seen through.
  bool enabled = true;
  /// A point is a border candidate when its shared neighbours, projected onto its tangent plane, leave an angular
  /// gap wider than this, degrees. A straight border leaves 180°, a convex corner more; around an inner point the
  /// largest gap among 16 random directions is about 60° and rarely passes 120°.
  float gap_threshold_deg = 120.f;
  /// A neighbour whose normal turns by more than this (degrees, either sign) from the point's marks a fold: a crease
  /// sharper than 90° projects its other face onto the same side and leaves a gap, and so does a 90° crease under the
  /// blended normals PCA gives next to it (a CAD part's edges seen edge-on lost their outline), but the surface goes
  /// on. Such a point is not a border point. A scan's border is smooth up to its last points.
  float fold_deg = 30.f;
  /// A candidate's neighbours reach no farther than this fraction of the neighbourhood radius r (the farthest
  /// shared neighbour) towards the gap: the point lies on the last row of points, not up to r inside, where a
  /// skewed neighbourhood can leave a gap too (traced lines ran 3–4 h inside a sheet's edge).
  float edge_band_fraction = 0.5f;
  /// Confirmation: no point lies in the cone of ±confirm_half_angle_deg around the gap's bisector (within 45° of the
  /// tangent plane) beyond the shared neighbours, out to confirm_factor × the distance of the farthest of them. Where
  /// the density changes (4:1 where scans overlap) the nearest neighbours all lie on the dense side and leave a gap
  /// towards the sparse one, whose points lie just beyond them; 3 × and ±30° expect about 8 of them in the cone.
  float confirm_factor = 3.f;
  float confirm_half_angle_deg = 30.f;
  /// A connected set of rim points spanning less than this (the largest side of its bounding box, units of h) is a
  /// small hole: not drawn, and not drawn as an outline either. Holes narrower than the cone (about 3r, some 14h at
  /// k = 16) are never confirmed as border: their rims are marked as a hole's from 2.5r (about 11h) on, and the
  /// sampling's own gaps (about 3h) not at all.
  float min_size_factor = 12.f;
  /// Tracing the border points into lines (paper §IV.A's growth). The border points of a random sampling lie about
  /// 2h apart along it, twice that where the density falls 4:1: r = 8h (the ridges use 6h) keeps the lines whole
  /// there (a hole's rim across 4:1 bands: 88% of it drawn at 6h, 96% at 8h).
  TraceOptions tracing{.radius_factor = 8.f};
  /// Joining broken border lines (pieces up to 2r apart join when aligned), dropping short ones (units of h),
  /// smoothing.
  JoinOptions joining{.join_distance_alpha = 2.f};
  ProgressFn progress;  ///< optional
};

struct Boundary {
  /// The values of `border` on a rim drawn as a boundary line, on one that is not drawn, and on an edge.
  static constexpr std::uint8_t kDrawnRim = 1, kUndrawnRim = 2, kEdge = 3;
  /// #P (empty when disabled): kDrawnRim on a rim drawn as a boundary line, kUndrawnRim on a rim that is not drawn (a
  /// small hole: its set spans under min_size_factor, or holds only points of a hole narrower than the cone), kEdge
  /// where the surface ends but is no such rim: the confirmation's cone holds a point (a scan recorded from one side
  /// stops at its interior contours, in front of the surface behind them), or the set of rim points is under 8, 0
  /// elsewhere. No stage draws an outline along the rims that are not drawn. The views draw every such point where
  /// the surface does not face the viewer and what lies beyond it in the image is far behind (depth edges,
  /// view::ContourOptions::depth_edge_factor).
  std::vector<std::uint8_t> border;
  std::vector<Polyline> lines;       ///< kind Boundary, view-independent, the cloud's relative coordinates
  std::size_t border_points = 0;     ///< points on a drawn border
  std::size_t small_holes = 0;       ///< connected sets of rim points not drawn (small, or a hole's rim only)
};

/// Finds the border points of the cloud (see BoundaryOptions), groups them into connected sets along the shared
/// neighbourhoods, and traces and joins those of the sets at least min_size_factor · h across into lines.
/// Deterministic. Near-linear: the confirmation's radius queries run only at the candidates.
/// @param positions #P relative positions
/// @param normals #P unit normals (their signs do not matter)
/// @param neighbourhoods the shared k-NN of `positions`
/// @param spacing mean spacing h, model units (> 0)
/// @param tree a kd-tree over `positions` to reuse for the confirmation's radius queries; null: one is built when
///        needed
/// @throws pcsketch::Error if the sizes disagree, h is not positive or an option is out of range.
Boundary find_boundaries(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                         const neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                         const BoundaryOptions& options = {}, const neighbourhood::KdTree* tree = nullptr);

}  // namespace pcsketch::features
