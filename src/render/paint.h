#pragma once
// Private to render/: what each backend paints, computed once from a Drawing so SVG, PDF and PNG agree exactly.

#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/render/options.h"

namespace pcsketch::render::detail {

/// A polyline drawn with one pen: constant width, round caps and joins.
struct Run {
  std::vector<Vec2f> points;  ///< pixels
  bool closed = false;
  float width = 1.f;  ///< pixels
  float grey = 0.f;   ///< 0 black … 1 white
  bool dashed = false;
};

/// One Stroke of the Drawing as one or more runs.
struct PaintStroke {
  std::size_t stroke = 0;  ///< index in Drawing::strokes
  std::vector<Run> runs;
};

struct PaintLayer {
  int number = 0;
  std::string_view label;             ///< "1 contours", …
  std::vector<PaintStroke> strokes;
  std::vector<std::size_t> regions;   ///< indices in Drawing::regions
};

/// Every layer, in paint order (shading, hidden, hatching, valleys, ridges, contours). Strokes with no point or a
/// non-finite coordinate are left out; a one-point stroke is a zero-length run (a round dot).
std::vector<PaintLayer> paint_layers(const Drawing& drawing, const RenderOptions& options);

/// Page size in PDF points (1/72 in) for the drawing and options.
std::array<double, 2> page_size_pt(const Drawing& drawing, const RenderOptions& options);

}  // namespace pcsketch::render::detail
