#pragma once
// Stroke thickness (paper §V): the depth model (eqs. 1–5), the angle model (eqs. 6–11, Table 1), their combination
// and a brush taper; turns the view's Polylines into Strokes with per-vertex and half-segment widths.
// Every width is in output pixels and depends only on the projected drawing, never on the cloud's scale.

#include <cstdint>
#include <optional>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/view/camera.h"

namespace pcsketch::stylize {

/// Which cue sets a vertex's thickness t_p.
enum class ThicknessModel : std::uint8_t {
  Constant,  ///< every vertex (ρ_min + ρ_max)/2: the paper's Fig. 19(d), lines before thickness diffusion
  Depth,     ///< §V.A: nearer is thicker, linear in depth between ρ_max (nearest) and ρ_min (farthest)
  Angle,     ///< §V.B: sharper bend is thicker, by the 10 levels of Table 1
  Combined,  ///< both, merged as `ThicknessOptions::combination` says
};

/// How the Combined model merges the depth width t_d and the angle width t_a (both in [0, ρ_max]).
enum class Combination : std::uint8_t {
  Mean,     ///< (1 − w)·t_d + w·t_a with w = `angle_weight`: a straight near line stays clearly visible
  Product,  ///< t_d·t_a/ρ_max: only near and bent parts get thick (straight lines fall to about ρ_min·t_d/ρ_max)
};

/// How an angle level (1 … 10, Table 1) becomes a width.
enum class AngleWidth : std::uint8_t {
  Range,  ///< ρ_min + (level − 1)/9·(ρ_max − ρ_min): straight = ρ_min, sharpest = ρ_max
  Paper,  ///< level/10·ρ_max: the paper's levels as fractions of the maximum thickness
};

/// Depth interval mapped onto [ρ_max, ρ_min] by the depth model (depth along the camera's forward axis, model units).
struct DepthRange {
  float near = 0.f;  ///< depth that gets ρ_max
  float far = 0.f;   ///< depth that gets ρ_min
};

/// Options of the thickness models. Widths are output pixels.
struct ThicknessOptions {
  ThicknessModel model = ThicknessModel::Combined;  ///< both cues, as the paper's Fig. 19(e) shows
  /// ρ_min: thinnest stroke, px. 0.8 px stays visible in an anti-aliased 1024 px PNG and on a 0.3 mm pen at 96 dpi.
  float rho_min = 0.8f;
  /// ρ_max: thickest stroke, px. 3 px is about 4× ρ_min: contrast that reads as depth without blobs at corners.
  float rho_max = 3.0f;
  /// cofi: the paper's control factor, multiplies every width (eqs. 4–5, 10–11). 1 keeps widths in [ρ_min, ρ_max].
  float cofi = 1.0f;
  /// Eqs. 4–5 as printed give two halves whose mean is 1.5× the mean of their end widths. When true (default) the
  /// halves are multiplied by 2/3 so that a segment between two vertices of width t is drawn with width t (the
  /// per-vertex widths mean what they say); false applies the paper's raw formula.
  bool normalise_cofi = true;
  Combination combination = Combination::Mean;  ///< Combined model only; Mean keeps straight near lines strong
  /// Combined/Mean: weight w of the angle width (0 … 1). 0.5: depth and bend count the same.
  float angle_weight = 0.5f;
  /// Angle model: the bend at a vertex is measured in the image between the points `angle_arm_px` of arc length
  /// before and after it, so that point-spacing noise does not make every vertex "sharp". 6 px: a few point
  /// spacings at the default image size, small enough to keep real corners. 0 = the paper's eq. 9 on the
  /// immediate 3D neighbours.
  float angle_arm_px = 6.0f;
  AngleWidth angle_width = AngleWidth::Range;  ///< Range uses the full [ρ_min, ρ_max] like the depth model
  /// Depth interval of the depth model. Default (nullopt): the depth range of all vertices passed to make_strokes
  /// (the whole drawing of one view, so that equal depths get equal widths across lines).
  std::optional<DepthRange> depth_range;
  /// Brush model (the paper's Fig. 19(e) "brush"): widths ramp up from `brush_end_fraction` of their value at the
  /// two ends of an open line over `brush_taper_px` of image arc length, like a brush lifted at both ends.
  bool brush = true;
  /// Taper length in px (at most half the line). 12 px: a clearly visible taper that leaves short lines their body.
  float brush_taper_px = 12.0f;
  /// Width at the very end as a fraction of the untapered width. 0.3 keeps the end visible at ρ_min.
  float brush_end_fraction = 0.3f;
};

/// Table 1: the level (1 … 10) of a bend angle α in degrees (180 = straight). Bins are closed on the right as in the
/// table: (0, 20] → 10, (20, 30] → 9, (30, 40] → 8, (40, 50] → 7, (50, 60] → 6, (60, 80] → 5, (80, 100] → 4,
/// (100, 120] → 3, (120, 150] → 2, (150, 180] → 1; α ≤ 0 (a full reversal) → 10.
int angle_level(double alpha_deg);

/// Bend angle α (eq. 9, degrees) at each vertex of `line`: with `arm_px` > 0 between the image points `arm_px` of
/// arc length before and after the vertex along `image_points` (#L, px); with `arm_px` = 0 between the immediate
/// 3D neighbours (the paper). Ends of open lines, and vertices whose arm is shorter than half `arm_px` (or zero),
/// get 180 (straight). Closed lines wrap around.
/// @return #L angles in degrees, in [0, 180].
std::vector<float> bend_angles_deg(const Polyline& line, const std::vector<Vec2f>& image_points, float arm_px);

/// The depth range of every vertex of `lines` seen by `camera` (depth as in Camera::project). Empty input: {0, 0}.
DepthRange depth_range(const std::vector<Polyline>& lines, const view::Camera& camera);

/// Per-vertex width t_p·cofi of one line (px) under the chosen model, including the brush taper.
/// @param[in] projected #L (u, v, depth) of the line's points, as Camera::project gives them.
/// @return #L widths, output pixels.
std::vector<float> stroke_widths(const Polyline& line, const std::vector<Vec3f>& projected, const DepthRange& range,
                                 const ThicknessOptions& options = {});

/// The half-segment rule (eqs. 4–5 / 10–11): segment p_front → p is drawn as two halves of widths
/// (t_front + t_p/2)·f and (t_front/2 + t_p)·f, where `widths` already carry cofi and f = 2/3 when
/// `normalise_cofi` (so equal ends give that width), else 1.
/// @return 2 per segment (segments include the closing one of a closed line), px.
std::vector<float> half_segment_widths(const std::vector<float>& widths, bool closed, bool normalise_cofi = true);

/// Strokes of one view, with the depth range the depth model used.
struct StrokesResult {
  std::vector<Stroke> strokes;
  std::vector<std::uint32_t> line;  ///< #S: the index in `lines` of the line each stroke was cut from
  DepthRange depth_range;
};

/// Turns the view's lines into strokes: widths per vertex from the whole line (so bends and tapers ignore visibility
/// breaks), then each line split into runs of equal visibility. Adjacent runs share the midpoint of the segment
/// where visibility changes, so visible and hidden strokes meet without a gap. The brush tapers only the real ends
/// of an open line, not visibility breaks (a line vanishing behind an occluder ends bluntly, like a T-junction).
/// Lines with fewer than 2 points give no stroke.
/// @param[in] lines the polylines of one view (contours, ridges, valleys); the depth range spans all of them.
/// @param[in] visible empty (all visible) or one entry per line, each empty (all visible) or #L flags (0 = hidden).
/// @throws pcsketch::Error when `visible` does not match `lines`, or ρ_min > ρ_max, or a negative width option.
StrokesResult make_strokes(const std::vector<Polyline>& lines, const view::Camera& camera,
                           const std::vector<std::vector<std::uint8_t>>& visible = {},
                           const ThicknessOptions& options = {});

}  // namespace pcsketch::stylize
