#pragma once
// SVG output, written as text (cairo's SVG surface cannot write Inkscape layers).

#include <filesystem>
#include <string>

#include "pcsketch/core/drawing.h"
#include "pcsketch/render/options.h"

namespace pcsketch::render {

/// The drawing as an SVG 1.1 document with one Inkscape layer per line kind, as vpype and AxiDraw read them:
/// `<g inkscape:groupmode="layer" inkscape:label="1 contours">`, "2 ridges", "3 valleys", "4 hatching",
/// "5 shading", "6 hidden". Every layer is written (possibly empty), in paint order: shading, hidden, hatching,
/// valleys, ridges, contours (lines over fills, contours on top). Each stroke is one element of its layer: a
/// `<path fill="none">` when it has one width (always in plotter mode), else a `<g>` of equal-width runs
/// (RenderOptions::width_step). Shade regions are filled `<path>`s. Coordinates are pixels (viewBox), origin
/// top-left; the camera and parameters are recorded as JSON in `<desc>`.
std::string svg_string(const Drawing& drawing, const RenderOptions& options = {});

/// Writes svg_string() to `path`. @throws pcsketch::Error if the file cannot be written.
void write_svg(const Drawing& drawing, const std::filesystem::path& path, const RenderOptions& options = {});

}  // namespace pcsketch::render
