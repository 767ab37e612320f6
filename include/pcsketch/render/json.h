#pragma once
// Machine-readable output: every stroke of the drawing (visible and hidden) with world and image coordinates.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "pcsketch/core/drawing.h"

namespace pcsketch::render {

/// The drawing as JSON (documented in docs/output.md):
/// {"image": {"width", "height"}, "origin": [x,y,z], "camera": {…}, "parameters": {…},
///  "polylines": [{"kind": "contour"|"ridge"|"valley"|"hatch", "visible", "closed", "grey",
///                 "points": [[x,y,z],…] (world: origin + point), "image_points": [[u,v],…] (pixels, origin
///                 top-left, v down), "widths": […] (px per vertex), "half_widths": […] (px, 2 per segment)}],
///  "regions": [{"grey", "polygon": [[u,v],…]}]}
/// Polylines are in Drawing::strokes order.
nlohmann::json to_json(const Drawing& drawing);

/// Writes to_json() to `path` (compact). @throws pcsketch::Error if the file cannot be written.
void write_json(const Drawing& drawing, const std::filesystem::path& path);

}  // namespace pcsketch::render
