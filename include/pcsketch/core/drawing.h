#pragma once
// A finished drawing of one view: strokes and shaded regions in image space, ready for any renderer.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pcsketch/core/polyline.h"

namespace pcsketch {

/// One pen stroke. Widths follow the paper's half-segment rule (§V, eqs. 4–5 and 10–11): segment i (points i → i+1)
/// is drawn as two halves, its first half with width half_widths[2i], its second with half_widths[2i+1].
struct Stroke {
  LineKind kind = LineKind::Contour;
  bool visible = true;              ///< hidden runs are kept (and drawn only on request, dashed)
  bool closed = false;              ///< the last point joins the first (one more segment)
  std::vector<Vec3f> points;        ///< #S, 3D, relative to the cloud's origin
  std::vector<Vec2f> image_points;  ///< #S, pixels, origin top-left, v down
  std::vector<float> widths;        ///< #S, per-vertex width t_p·cofi, output pixels
  std::vector<float> half_widths;   ///< 2 per segment, output pixels (see above)
  float grey = 0.f;                 ///< ink level: 0 = black … 1 = white (hatch strokes get lighter far from the line)
  /// Set when this stretch runs along another stroke and is drawn once, as that one (paper Fig. 2(d) "fused"):
  /// the index, in Drawing::strokes, of the stroke drawn in its place. Kept in the JSON, not painted.
  std::optional<std::uint32_t> fused_into;

  std::size_t segments() const { return points.size() < 2 ? 0 : points.size() - 1 + (closed ? 1 : 0); }
  /// Length of the drawn line in the image, px (the closing segment included).
  float image_length() const {
    float length = 0.f;
    for (std::size_t k = 0; k < segments(); ++k)
      length += (image_points[(k + 1) % image_points.size()] - image_points[k]).norm();
    return length;
  }
};

/// A filled region (shadow block, paper §VI.B "area 1 > area 2 > area 3").
struct ShadeRegion {
  std::vector<Vec2f> polygon;  ///< pixels, closed implicitly
  float grey = 0.5f;           ///< 0 = black … 1 = white
};

/// Text on the page: a scale bar's figures, a view's name.
struct Label {
  Vec2f position = Vec2f::Zero();  ///< pixels: the baseline's start, middle or end (see `anchor`)
  std::string text;
  float size = 12.f;  ///< font size, pixels
  enum class Anchor { Start, Middle, End } anchor = Anchor::Start;
};

/// What the page adds around the model's lines (scale bar, north arrow, view names): drawn in a layer of its own,
/// black, never fused, sorted or thickened.
struct Annotations {
  std::vector<std::vector<Vec2f>> lines;  ///< open polylines, pixels
  std::vector<std::vector<Vec2f>> fills;  ///< filled polygons (scale-bar cells, arrow head), pixels
  std::vector<Label> labels;
  float width = 1.f;                      ///< line width, pixels
  bool empty() const { return lines.empty() && fills.empty() && labels.empty(); }
};

/// Everything a renderer needs, plus what reproduces it.
struct Drawing {
  int width = 0, height = 0;       ///< pixels
  Vec3d origin = Vec3d::Zero();    ///< the cloud's origin: world = origin + point
  nlohmann::json camera;           ///< Camera::to_json()
  nlohmann::json parameters;       ///< every option used, for reproducibility
  nlohmann::json plotter;          ///< plotter paths only: pen travel before and after ordering (else null)
  nlohmann::json input;            ///< what the read kept when it thinned the file (else null): docs/io.md
  /// Page millimetres per pixel fixed by a stated scale (page::PageOptions::scale); the writers then size the page
  /// from it instead of RenderOptions::page_width_mm. Unset: the page follows the render options.
  std::optional<double> page_mm_per_pixel;
  Annotations annotations;
  std::vector<Stroke> strokes;
  std::vector<ShadeRegion> regions;
};

}  // namespace pcsketch
