#pragma once
// How a Drawing becomes SVG, PDF or PNG: what is drawn (hidden lines, shading, plotter centre-lines) and the page size.

#include <nlohmann/json_fwd.hpp>
#include <optional>

#include "pcsketch/core/drawing.h"

namespace pcsketch::render {

/// Hidden runs of lines (Stroke::visible == false) are always kept in the Drawing and the JSON; this decides whether
/// the SVG/PDF/PNG show them.
enum class HiddenLines {
  None,    ///< not drawn (the paper's drawings)
  Dashed,  ///< thin dashed grey in a layer of their own, the technical-illustration convention
};

struct RenderOptions {
  /// Draw hidden runs of contours, ridges and valleys (never hidden hatching).
  HiddenLines hidden_lines = HiddenLines::None;
  /// Pen-plotter output: every stroke as its centre-line with the single width `pen_width`, black, no shade regions
  /// (a plotter draws lines; variable width and grey fills are what it cannot draw).
  bool plotter = false;
  /// Plotter mode: line width in page millimetres (the page of `page_width_mm`, or CSS pixels of 1/96 in). 0.3 mm is
  /// a fine pen.
  double pen_width_mm = 0.3;
  /// Plotter mode: line width in image pixels instead of `pen_width_mm` (the unit of `--pen-width` before pen widths
  /// were millimetres; 1 px ≈ 0.26 mm on the default page).
  std::optional<float> pen_width;
  /// Width in pixels of strokes that carry no widths (a Drawing made without the thickness stage).
  float default_width = 1.5f;
  /// Variable-width strokes are drawn as runs of equal width (round caps and joins, so runs meet seamlessly): a
  /// half-segment's width is rounded to a multiple of this step in pixels and neighbouring half-segments of the same
  /// rounded width form one run. 0.25 px is below what the eye resolves and keeps an SVG's path count low; 0 makes
  /// every half-segment a run of its own (exact widths).
  float width_step = 0.25f;
  /// Hidden lines (when drawn): width in pixels, grey level (0 black … 1 white) and dash length = gap length in px.
  float hidden_width = 0.6f;
  float hidden_grey = 0.55f;
  float hidden_dash = 4.0f;
  /// Draw the Drawing's ShadeRegions (grey filled blocks) in the shading layer. Ignored in plotter mode.
  bool shading = true;
  /// Physical page width of SVG and PDF output in millimetres; the height follows the image's aspect ratio and
  /// all coordinates stay in pixels (SVG viewBox). Unset: the page is width × height CSS pixels (1 px = 1/96 in,
  /// PDF: 0.75 pt). PNG is always width × height pixels.
  std::optional<double> page_width_mm;
  /// Decimals written for SVG coordinates (pixels): 2 is a hundredth of a pixel, far below any output resolution.
  int decimals = 2;

  nlohmann::json to_json() const;
};

/// Page millimetres per image pixel of `drawing`: its stated scale's (Drawing::page_mm_per_pixel) when set, else
/// page_width_mm / width, or 25.4 / 96 (a CSS pixel) when the page width is unset too.
double mm_per_pixel(const Drawing& drawing, const RenderOptions& options);

/// Whether the page of `drawing` is measured in millimetres (a stated scale or page_width_mm), not CSS pixels.
bool page_in_mm(const Drawing& drawing, const RenderOptions& options);

/// The plotter pen's width in image pixels: `pen_width` when set, else `pen_width_mm` on the page.
float pen_width_px(const Drawing& drawing, const RenderOptions& options);

}  // namespace pcsketch::render
