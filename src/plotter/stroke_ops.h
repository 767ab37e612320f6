#pragma once
// Private to plotter/: what merging and sorting do to one stroke, and the collinear hatch pass.

#include <vector>

#include "pcsketch/core/drawing.h"
#include "end_grid.h"

namespace pcsketch::plotter::detail {

/// Length of the stroke's image polyline in pixels, the closing segment included.
double image_length(const Stroke& s);

/// Pen position where the stroke starts and where it ends (a closed stroke ends where it starts).
Vec2d first_point(const Stroke& s);
Vec2d last_point(const Stroke& s);

/// The stroke drawn the other way: every per-vertex and per-half-segment array reversed.
void reverse(Stroke& s);

/// Appends `next` (open) to the end of `into` (open). Coinciding ends share one vertex; otherwise a connecting
/// segment is drawn. 3D points, widths and half widths follow when both strokes carry them, and are cleared
/// otherwise (the pen has one width).
void append(Stroke& into, const Stroke& next);

/// Straight open hatch strokes on one line (within `tolerance_px` of it) merged into one stroke per overlapping
/// stretch (pieces less than `tolerance_px` apart count as overlapping). Other strokes pass unchanged.
/// @param[out] removed_px hatch length no longer drawn twice, pixels
std::vector<Stroke> merge_collinear(std::vector<Stroke> strokes, double tolerance_px, double& removed_px);

}  // namespace pcsketch::plotter::detail
