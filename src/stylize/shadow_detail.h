#pragma once
// Pieces shared by the two shadow modes (private to the stylize stage).

#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/stylize/shadow.h"

namespace pcsketch::stylize::detail {

/// A visible Hatch stroke of constant width and grey through `points` (3D) and their `image_points` (px).
Stroke hatch_stroke(std::vector<Vec3f> points, std::vector<Vec2f> image_points, bool closed, float width, float grey);

/// Linear interpolation between a (i = 0) and b (i = count − 1); a when count < 2.
float graded(float a, float b, std::size_t i, std::size_t count);

/// Attached-shadow hatching (ShadowMode::Attached), `light` the unit travel direction.
std::vector<Stroke> attached_hatching(const ShadowInput& input, const ShadowOptions& options, const Vec3f& light);

}  // namespace pcsketch::stylize::detail
