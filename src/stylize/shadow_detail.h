#pragma once
// Pieces shared by the two shadow modes (private to the stylize stage).

#include <array>
#include <cstdint>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/stylize/shadow.h"

namespace pcsketch::stylize::detail {

/// A visible Hatch stroke of constant width and grey through `points` (3D) and their `image_points` (px).
Stroke hatch_stroke(std::vector<Vec3f> points, std::vector<Vec2f> image_points, bool closed, float width, float grey);

/// Linear interpolation between a (i = 0) and b (i = count − 1); a when count < 2.
float graded(float a, float b, std::size_t i, std::size_t count);

/// The view's silhouette: image cells covered by some point's disc (any orientation), the drawing's filled outline.
struct SilhouetteMask {
  int w = 0, h = 0;
  float cell = 1.f;                  ///< px
  std::vector<std::uint8_t> inside;  ///< w·h
  bool contains(const Vec2f& p) const;
};

/// Every point splatted as a round disc of its scene radius (splat_radius_factor × local spacing) into cells of
/// mask_cell_px.
SilhouetteMask silhouette_mask(const ShadowInput& input, const ShadowOptions& options);

/// The pieces of a hatch stroke inside `mask`, sampled at half a cell (3D points interpolated along each segment).
std::vector<Stroke> clip_stroke(const Stroke& stroke, const SilhouetteMask& mask);

/// A shade block given per line vertex by (base on the line, inner boundary, outer boundary) image points, the
/// three collinear: resampled at half a cell along the line, each sample's cross segment cut where the way out
/// from the base first leaves `mask`. @return the polygons (inner boundary forward, outer back) that remain.
std::vector<std::vector<Vec2f>> clip_block(const std::vector<std::array<Vec2f, 3>>& cross, const SilhouetteMask& mask);

/// Attached-shadow hatching (ShadowMode::Attached), `light` the unit travel direction.
std::vector<Stroke> attached_hatching(const ShadowInput& input, const ShadowOptions& options, const Vec3f& light);

}  // namespace pcsketch::stylize::detail
