#pragma once
// Contours of one view (paper §IV.B): the outline of the projected cloud (boundary points of the 2D point set, traced
// by direction-guided growth) and, beyond the paper, interior occluding contours where the surface turns away from
// the viewer inside the outline (an ear in front of the head, the inner rim of a torus seen from the side).

#include <cstdint>
#include <limits>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/view/camera.h"

namespace pcsketch::view {

/// How the outline's boundary points are chained (docs/views.md compares them).
enum class OutlineConnection : std::uint8_t {
  /// The paper's rule: the nearest unused boundary point ahead whose distance to the direction line is below z_max.
  DirectionGuided,
  /// Default: among the unused boundary points within the trace radius and the turn limit, the one furthest toward
  /// the empty side (gift wrapping). Interference points lie inside the outline, so they are never taken: no
  /// zig-zags, and the line follows the outermost points (within a pixel of the true silhouette).
  Outermost,
};

/// Options of contour extraction. Lengths marked "h_px" are in units of the projected spacing: the mean spacing h
/// seen at the point's depth, in pixels (orthographic: h · camera.scale).
struct ContourOptions {
  // --- contour points extraction (paper: boundary points of the projected set) ---
  /// 2D neighbourhood radius r, in units of h_px. A random sampling has about 1/(4h²) points per unit area and a
  /// closed surface projects at least two layers, so r = 3 sees about 28 neighbours (7 on a single face-on layer);
  /// the confirmation below rejects what sparse single layers get wrong.
  float radius_factor = 3.0f;
  /// Paper's k: the largest gap is taken among at most the k nearest neighbours within r. The scan stops early,
  /// as interior, once the points within r fill all eight 45° sectors (docs/views.md).
  std::size_t k = 32;
  /// A point is a boundary point when the largest angle between consecutive neighbour directions exceeds this, in
  /// degrees. A point on a straight outline sees 180°; 120° keeps the band of boundary points within r/2 of the
  /// outline and rarely fires inside (the largest gap among ~28 random directions is about 50°).
  float gap_threshold_deg = 120.0f;
  /// Paper: also a boundary point when one of the four quadrants of the (u, v) frame at the point is empty. Off by
  /// default: that test depends on the image axes and marks points up to 0.7 r inside a straight outline.
  bool quadrant_test = false;
  /// Beyond the paper: a candidate is kept only if the cone of ±confirm_half_angle_deg around its empty direction
  /// holds no point between r and confirm_factor · r. Outside a real outline the empty region goes on; a hole of
  /// the random sampling inside the outline (they reach about r) is closed beyond it. 1 disables the check.
  float confirm_factor = 2.0f;
  /// Half-angle of the confirmation cone, degrees. Narrow: concave notches down to about r wide keep their outline.
  float confirm_half_angle_deg = 20.0f;

  // --- contour connection (paper: direction-guided growth) ---
  OutlineConnection connection = OutlineConnection::Outermost;
  /// Radius within which the next point of a line is searched, in units of h_px (paper: the neighbourhood of k).
  float trace_radius_factor = 3.0f;
  /// Radius of the disc that closes the outline's gaps, in units of h_px (0: off). From each open end of the traced
  /// outline a disc of this radius rolls along the outermost projected points until it meets the outline again
  /// (2D ball pivoting), so gaps up to twice the radius between outermost points are bridged. Sparse clouds need it:
  /// there the gap test passes only every few rim points, further apart than the trace radius (docs/views.md).
  float bridge_radius_factor = 2.5f;
  /// Paper's z_max: largest distance of the next point from the direction line, in units of h_px (DirectionGuided).
  float z_max_factor = 1.0f;
  /// Largest turn between consecutive steps, degrees; rejects backtracking (the spikes of interference points).
  float max_turn_deg = 120.0f;
  /// Unused boundary points within this distance beside or behind a step are removed ("used points removed"), in
  /// units of h_px: the band of boundary points (r/2 wide) must not seed a second, parallel line.
  float absorb_factor = 1.5f;
  /// The direction n_p = p_front − p is taken over this many previous steps: smooths the heading on noisy bands.
  std::size_t heading_steps = 3;
  /// Lines shorter than this (units of h, measured in 3D for interior contours and in h_px for the outline) are
  /// dropped: stray boundary points and rim samples make short fragments. 4 keeps the short visible pieces of
  /// interior contours that end at cusps.
  float min_length_factor = 4.0f;

  // --- interior contours (beyond the paper) ---
  /// Add occluding contours where the normal turns from facing the viewer to facing away (n·v changes sign between
  /// neighbours), located at the zero crossing. Needs oriented normals and neighbourhoods.
  bool interior = true;
  /// Neighbours examined for a sign change (the nearest of the k-NN list): a wider ring blurs the zero crossing.
  std::size_t interior_neighbours = 8;
  /// Beyond the paper: neighbours whose normals differ by more than this make no rim sample, degrees (180: off). A
  /// rim turns the normal smoothly through the view plane, and a crease seen from the side by its dihedral angle (90°
  /// on a cube); normals further apart within a few neighbours are a thin part's two sides, or a patch whose
  /// orientation flipped (noise, thin parts), whose border n·v crosses firmly. 90: docs/views.md, "Opposite normals".
  float interior_max_normal_angle_deg = 90.0f;
  /// Rim samples within this 3D distance of an outline vertex belong to the outline already, in units of h.
  float interior_dedupe_factor = 3.0f;
  /// 3D search radius when chaining rim samples, in units of h. Rim samples lie about 2h apart along the
  /// generator on random samplings (h is the mean nearest-neighbour distance, half the typical spacing).
  float interior_trace_radius_factor = 6.0f;
  /// Paper's z_max for the interior tracing: largest distance of the next rim sample from the direction line, in
  /// units of h. The rim samples scatter about h around the generator on both sides; 2.5 keeps chains unbroken
  /// (mesh ground truth: recall +5% over 1.5 at unchanged precision).
  float interior_z_max_factor = 2.5f;
  /// Beyond the paper: a sign change of n·v makes a rim sample only if it persists: the point on each side has, among
  /// itself and its interior_neighbours, one with |n·v| ≥ persistence_factor × the normals' angular noise
  /// (Surface::normal_noise) on its own side. Noisy normals flip the sign of n·v wherever it is small (a face seen
  /// edge-on, the band around a rim); a real rim has n·v growing away from it on both sides. Clean clouds have a
  /// noise near 0, which leaves them as they were. 0 accepts every sign change (the rule before it).
  float persistence_factor = 2.0f;
  /// Beyond the paper: on a denoised cloud (differential::Surface::denoised) interior contours shorter than this many
  /// h are dropped. What noise leaves after persistence are squiggles of 5–20 h on grazing surfaces (legs, flanks,
  /// faces seen edge-on). Measured (bench_scans, 200k samples, 3 views, σ = 0.1% / 0.2%, contour P min, R min):
  /// 4 → 20 raised the fandisk's precision at 0.1% from 0.88 to 0.97 and the camel's at 0.2% from 0.68 to 0.80,
  /// for 0.01–0.07 of recall; on clean clouds (not denoised) it costs 0.02–0.06 of recall, so they keep
  /// min_length_factor.
  float denoised_min_length_factor = 20.0f;
  /// Beyond the paper: on a denoised cloud, an interior contour shorter than denoised_min_length_factor keeps
  /// min_length_factor when most of its rim samples bend: n·v over a sample's point, its interior_neighbours and
  /// theirs changes with position across the tangent plane (the F statistic of a plane fit against a constant, 2 and
  /// about 40 degrees of freedom, reaches this). Noise on a face seen nearly edge-on flips the sign of n·v with no
  /// such trend; a short rim of fine relief has one. 16 is far above what noise alone reaches (F(2, 40) exceeds 8.3
  /// once in 1000). 0: every short contour is kept; 1e30: none bends (with denoised_min_bending 0, the length rule
  /// alone). docs/views.md, "Bending".
  float bend_min_f = 16.0f;
  /// Beyond the paper: on a denoised cloud, an interior contour fewer of whose rim samples than this share bend (see
  /// bend_min_f) is dropped whatever its length, unless it is mostly depth edges. Where a sheet is thinner than a few
  /// σ of noise (the held-out blade at σ = 0.2%: 2.5σ thick), its two sides interleave, n·v changes sign all over it
  /// and the squiggles chain past any length; under 30% of their samples bend, where on seven other models the
  /// chains of 20 h or more have over 30% on 89–100% of their length. 0: off. docs/views.md, "Long squiggles".
  float denoised_min_bending = 0.3f;
  /// Beyond the paper: depth edges. A scan recorded from one side has no points past its interior contours, so n·v
  /// never changes sign there. A point is a rim sample when the surface ends at it (the border search marks it:
  /// find_contour_points' `border` is not 0 there; no border, no depth edges), it does not face the viewer
  /// (|n·v| ≤ 0.5), its projected neighbours leave a gap over gap_threshold_deg in the image, and every point within
  /// depth_edge_radius_factor projected spacings beyond that gap (±confirm_half_angle_deg) lies more than this many
  /// h behind it (and there is one). The samples take the mean depth of the edge points among their
  /// interior_neighbours. 10: the same surface curving away within the radius lies 4–7 h behind a gap of its
  /// sampling (the clean bunny's), the other candidates there lay 20 h or more behind. A chain mostly of depth-edge
  /// samples keeps min_length_factor on a denoised cloud too: it is no squiggle of noisy normals. docs/views.md,
  /// "Depth edges". 0: off.
  float depth_edge_factor = 10.0f;
  /// Image radius of the depth-edge test, in projected spacings (see depth_edge_factor).
  float depth_edge_radius_factor = 6.0f;

  // --- the outline's scale ---
  /// Beyond the paper: the h_px of the outline's lengths (r, trace radius, z_max, absorb, min length) is each point's
  /// local spacing where the cloud is sparser than average: the larger of h and the distance to its 16th neighbour,
  /// averaged over its neighbours and scaled so that its median over the cloud is h. Mesh vertices and merged scans
  /// are uneven; at the global h the sparse parts of a camel's body (triangles several h wide) read as holes, and
  /// its outline broke into pieces with zig-zags. Mesh ground truth, 7 views, mean contour precision / recall:
  /// camel vertices 0.918 / 0.698 → 0.928 / 0.735, bunny 0.989 / 0.921 → 0.987 / 0.924, elephant (2,775 vertices)
  /// 0.770 / 0.602 → 0.741 / 0.585. Interior contours keep h: a local unit there lost recall on all three.
  /// Off: the paper's single radius everywhere.
  bool adaptive_spacing = true;
  ProgressFn progress;  ///< optional: "contour points", "contour connection"
};

/// The contour points of one view (the "contour points extraction" step).
struct ContourPoints {
  std::vector<Vec3f> projected;        ///< #P: (u, v, depth) of every point (camera.project)
  std::vector<float> spacing_px;       ///< #P: the point's spacing unit at its depth, pixels (h_px; see adaptive_spacing)
  std::vector<std::uint32_t> boundary; ///< #B: indices of the outline's boundary points, ascending
  std::vector<Vec2f> outward;          ///< #B: unit image direction of each boundary point's largest empty gap
  std::vector<Vec3f> rim;              ///< #R: interior rim samples (zero crossings of n·v), relative coordinates
  std::vector<std::uint32_t> rim_point;  ///< #R: the cloud point each rim sample was made from
  /// Per interior rim sample (those before depth_edges_begin) of a denoised cloud: whether n·v bends across it (see
  /// bend_min_f). Empty otherwise: then no sample counts as bending.
  std::vector<char> rim_bends;
  /// Rim samples from this index on are depth edges' (see depth_edge_factor); past the end: none.
  std::size_t depth_edges_begin = std::numeric_limits<std::size_t>::max();
};

/// Projects the cloud and finds the outline's boundary points (paper §IV.B) and, when `options.interior`, the rim
/// samples of interior contours.
/// @param positions #P relative positions
/// @param normals #P oriented unit normals (only read when options.interior; may then not be empty)
/// @param neighbourhoods the 3D k-NN lists of the cloud (the outline's pre-filter and the border band read them when
///   given; interior contours need them)
/// @param spacing mean spacing h, model units (> 0)
/// @param normal_noise angular noise of the normals, radians (Surface::normal_noise; see persistence_factor)
/// @param border empty or #P: the rims of an open scan (features::Boundary::border). Points of a rim that is not
///   drawn (2: a small hole) and their nearest interior_neighbours are no outline points: the surface ends there, and
///   such a hole is not drawn at all. Along a drawn border (1) the outline may run: the boundary line is drawn over
///   it (fusion), and where its tracing left a stretch of a sparse border out, the outline still closes.
/// @param denoised the cloud was denoised (Surface::denoised): ContourPoints::rim_bends is then filled, for
///   connect_contours with the same flag
/// @throws pcsketch::Error for a non-positive spacing, missing normals/neighbourhoods when interior is on, or a
///   border of the wrong size.
ContourPoints find_contour_points(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                  const neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                                  const Camera& camera, const ContourOptions& options = {}, float normal_noise = 0,
                                  const std::vector<std::uint8_t>& border = {}, bool denoised = false);

/// The contour lines of one view, all of kind Contour.
struct ContourLines {
  /// Outline of the projection: vertices are cloud points (point_index set), closed when the outline closes. Seen
  /// by construction: nothing projects beyond the outline of everything.
  std::vector<Polyline> outline;
  /// Interior occluding contours: vertices are rim samples, point_index the cloud point each came from.
  /// Partly hidden in general (the far rim of a torus hole); visibility decides.
  std::vector<Polyline> interior;
};

/// Chains the contour points into polylines (the "contour connection" step): the outline first, then the interior
/// contours not already covered by it. Deterministic.
/// @param denoised the cloud was denoised (interior contours then need denoised_min_length_factor, unless they are
///        mostly depth edges or bend: ContourPoints::rim_bends, which find_contour_points fills when told so too;
///        and, where rim_bends is filled, denoised_min_bending)
ContourLines connect_contours(const ContourPoints& points, const std::vector<Vec3f>& positions, float spacing,
                              const ContourOptions& options = {}, bool denoised = false);

}  // namespace pcsketch::view
