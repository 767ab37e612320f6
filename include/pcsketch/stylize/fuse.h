#pragma once
// Fusion of doubled lines (paper Fig. 2(d), "optimized and fused"): where two strokes run side by side within a pen
// width or two of each other in the image (a contour and the ridge along the same edge, an outline and an interior
// contour traced along the same rim), the stretch is drawn once. The stroke that is not drawn there is kept, cut at
// the ends of the stretch, and marked Stroke::fused_into the one drawn in its place.

#include <cstdint>
#include <vector>

#include "pcsketch/core/drawing.h"

namespace pcsketch::stylize {

struct FusionOptions {
  bool enabled = true;  ///< false draws every line as traced (the paper's Fig. 2(c))
  /// Two strokes run together where they are closer than this, in pen widths (ρ_max·cofi, px). 2: the doubles of
  /// issue 13 (a contour and a ridge, or two tracings of one rim) are 2–5 px apart at the default ρ_max = 3 px,
  /// while distinct features closer than two pen widths cannot be told apart on paper either.
  float distance_widths = 2.f;
  /// A stretch is fused only when it is at least this long along the stroke not drawn, px. 10 px (about three pen
  /// widths): lines that cross or merely touch stay, only lines that run alongside each other are drawn once. A
  /// contour within half a pen width of another line over its whole length is fused however short: it is a double
  /// (the pieces an interior contour leaves beside the outline), and the angle test holds at each of its vertices.
  float min_stretch_px = 10.f;
  /// A gap shorter than this (px) between two stretches fused into the same stroke is fused too: two tracings of one
  /// rim hover about the fusion distance, and the line drawn would otherwise switch between them. 30 px = 3 stretches.
  float max_gap_px = 30.f;
  /// Largest angle between the two strokes' directions along a stretch, degrees (undirected): crossing lines are
  /// two lines even where they are close.
  float max_angle_deg = 30.f;
};

/// Precedence of a stroke in fusion: where two strokes run together the one of lower rank is drawn.
enum class FusionRank : std::uint8_t {
  Boundary = 0,  ///< the border of an open scan: where the outline runs along it, the line keeps the border's kind
  Outline = 1,   ///< the outline contour
  Interior = 2,  ///< interior occluding contours
  Feature = 3,   ///< ridge and valley lines
  None = 255,    ///< takes no part (hatching)
};

struct FusionResult {
  /// The input strokes in their order, each cut into runs at the ends of its fused stretches: #S' ≥ #S.
  std::vector<Stroke> strokes;
  std::size_t fused_stretches = 0;  ///< strokes marked fused_into another
};

/// Fuses strokes that run alongside each other. Only visible strokes of rank other than None take part. Of two
/// strokes, the lower rank is drawn; between equal ranks the longer (in the image), then the earlier. Each vertex of
/// a stroke is matched against the segments of the strokes that precede it in that order and are drawn there,
/// through a uniform grid over the image (cells of the fusion distance), so the cost is linear in the vertices for
/// lines that are not all piled in one place.
/// @param strokes the view's line strokes (make_strokes), image points in px
/// @param rank #S, one per stroke
/// @param pen_width_px the unit of `distance_widths`: the thickest stroke, ρ_max·cofi
/// @throws pcsketch::Error when `rank` does not match `strokes`.
FusionResult fuse_strokes(std::vector<Stroke> strokes, const std::vector<FusionRank>& rank, float pen_width_px,
                          const FusionOptions& options = {});

}  // namespace pcsketch::stylize
