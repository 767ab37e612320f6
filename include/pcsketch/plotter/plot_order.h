#pragma once
// Pen-plotter paths: the strokes of a finished Drawing merged where their ends meet (vpype's `linemerge`), collinear
// duplicate hatch strokes drawn once, dabs dropped, and each layer sorted to shorten pen-up travel (vpype's
// `linesort`). Lengths are page millimetres: the caller gives the page's millimetres per image pixel.

#include <cstddef>
#include <nlohmann/json_fwd.hpp>

#include "pcsketch/core/drawing.h"

namespace pcsketch::plotter {

struct PlotterOptions {
  /// Stroke ends closer than this are joined into one stroke, reversing strokes where needed, page mm. vpype's
  /// `linemerge` default is 0.05 mm; hatch lines broken at depth jumps leave gaps of one pixel (0.2 mm on a 200 mm
  /// page of 1024 px), which a 0.3 mm pen closes anyway.
  double merge_tolerance_mm = 0.2;
  /// Straight hatch strokes lying on one line within this distance, page mm, are one line: their overlapping
  /// pieces are drawn once (pieces of one hatch line from different shading steps).
  double collinear_tolerance_mm = 0.05;
  /// Strokes shorter than this after merging are left out, page mm: the pen would only dab a dot. 0 keeps all.
  double min_stroke_mm = 0.5;
  bool merge = true;  ///< join strokes whose ends meet (per layer)
  bool sort = true;   ///< greedy nearest-end order with reversal (per layer)
};

/// What the pen does for one drawing: ink laid and travel in the air, summed over the layers (a layer is plotted as
/// one pass; the travel from one layer to the next and from the home position is not counted).
struct PlotStats {
  double pen_down_mm = 0;   ///< length of the drawn strokes
  double pen_up_mm = 0;     ///< from each stroke's end to the next stroke's start within its layer
  std::size_t strokes = 0;  ///< pen-downs

  nlohmann::json to_json() const;
};

struct PlotterResult {
  Drawing drawing;                        ///< the strokes in plotting order, layer by layer
  PlotStats before;                       ///< the input drawing as the writers would plot it
  PlotStats after;                        ///< the result
  std::size_t joins = 0;                  ///< stroke ends joined by merging
  double duplicate_hatching_mm = 0;       ///< hatch length removed as drawn twice or more
  std::size_t short_strokes_dropped = 0;  ///< strokes under min_stroke_mm
};

/// The plotted strokes of a drawing: visible strokes grouped by kind (the SVG layers), hidden non-hatch strokes as
/// one layer when `hidden_drawn` (--hidden-lines dashed), otherwise left out. Strokes with no point or a non-finite
/// image coordinate are left out (the writers skip them too).
/// @param mm_per_pixel page millimetres per image pixel (render::mm_per_pixel)
PlotStats plot_stats(const Drawing& drawing, double mm_per_pixel, bool hidden_drawn = false);

/// Plotter order of `drawing`. Within each layer: straight hatch strokes on one line merged into one per
/// overlapping stretch; strokes whose ends lie within merge_tolerance_mm joined (3D points, image points and widths
/// concatenated, a stroke reversed when needed; closed strokes are kept whole); strokes shorter than min_stroke_mm
/// dropped; then a greedy nearest-end order from the page origin, reversing strokes whose far end is nearer. The
/// greedy order is kept only when it travels less than the input order, so pen-up travel never grows. Strokes not
/// plotted (hidden ones unless `hidden_drawn`) are left out of the result. Near-linear: ends are looked up in a
/// uniform grid. @param mm_per_pixel page millimetres per image pixel (render::mm_per_pixel), positive.
PlotterResult plot_order(const Drawing& drawing, double mm_per_pixel, const PlotterOptions& options = {},
                         bool hidden_drawn = false);

}  // namespace pcsketch::plotter
