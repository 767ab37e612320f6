// Shading stays on the object: the silhouette of the view as a mask, and the clipping of hatch strokes and shade
// blocks against it.

#include <algorithm>
#include <array>
#include <cmath>

#include "stylize/shadow_detail.h"

namespace pcsketch::stylize::detail {

bool SilhouetteMask::contains(const Vec2f& p) const {
  if (!p.allFinite()) return false;
  const float x = std::floor(p.x() / cell), y = std::floor(p.y() / cell);
  if (x < 0.f || y < 0.f || x >= static_cast<float>(w) || y >= static_cast<float>(h)) return false;
  return inside[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] != 0;
}

SilhouetteMask silhouette_mask(const ShadowInput& in, const ShadowOptions& o) {
  const view::Camera& cam = in.camera;
  SilhouetteMask m;
  m.cell = o.mask_cell_px;
  m.w = std::max(1, static_cast<int>(std::ceil(static_cast<float>(cam.width) / m.cell)));
  m.h = std::max(1, static_cast<int>(std::ceil(static_cast<float>(cam.height) / m.cell)));
  m.inside.assign(static_cast<std::size_t>(m.w) * static_cast<std::size_t>(m.h), 0);
  // Every point as a round splat of its disc radius, whichever way it faces: the filled outline of the drawing.
  // Serial: the writes of neighbouring splats overlap, and one pass over the points is cheap next to the shading.
  for (std::size_t i = 0; i < in.positions.size(); ++i) {
    const Vec3f uvd = cam.project(in.positions[i]);
    if (!(uvd.z() > 0.f) || !uvd.allFinite()) continue;
    const float r = o.splat_radius_factor * in.local_spacing[i] / cam.units_per_pixel(uvd.z()) / m.cell;
    if (!(r > 0.f) || !std::isfinite(r)) continue;
    const float cx = uvd.x() / m.cell, cy = uvd.y() / m.cell;
    if (cx >= 0.f && cy >= 0.f && cx < static_cast<float>(m.w) && cy < static_cast<float>(m.h))
      m.inside[static_cast<std::size_t>(cy) * m.w + static_cast<std::size_t>(cx)] = 1;  // a disc smaller than a cell
    const int y0 = std::max(0, static_cast<int>(std::floor(std::max(cy - r, -1.f))));
    const int y1 = std::min(m.h - 1, static_cast<int>(std::floor(std::min(cy + r, static_cast<float>(m.h)))));
    const int x0 = std::max(0, static_cast<int>(std::floor(std::max(cx - r, -1.f))));
    const int x1 = std::min(m.w - 1, static_cast<int>(std::floor(std::min(cx + r, static_cast<float>(m.w)))));
    // A cell is in when its centre lies on the disc: the mask then reaches at most half a cell's diagonal past it.
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const float dx = static_cast<float>(x) + 0.5f - cx, dy = static_cast<float>(y) + 0.5f - cy;
        if (dx * dx + dy * dy <= r * r) m.inside[static_cast<std::size_t>(y) * m.w + x] = 1;
      }
  }
  return m;
}

std::vector<Stroke> clip_stroke(const Stroke& s, const SilhouetteMask& mask) {
  std::vector<Stroke> out;
  const std::size_t n = s.image_points.size();
  std::vector<Vec3f> points;
  std::vector<Vec2f> image;
  bool cut = false;
  auto flush = [&](bool closed) {
    if (points.size() >= 2)
      out.push_back(hatch_stroke(std::move(points), std::move(image), closed, s.widths.front(), s.grey));
    points.clear();
    image.clear();
  };
  for (std::size_t k = 0; k < s.segments(); ++k) {
    const std::size_t b = (k + 1) % n;
    const Vec2f &ia = s.image_points[k], &ib = s.image_points[b];
    const int steps = std::clamp(static_cast<int>(std::ceil(2.f * (ib - ia).norm() / mask.cell)), 1, 1 << 16);
    for (int t = k == 0 ? 0 : 1; t <= steps; ++t) {
      const float u = static_cast<float>(t) / static_cast<float>(steps);
      const Vec2f p = ia + u * (ib - ia);
      if (!mask.contains(p)) {
        cut = true;
        flush(false);
        continue;
      }
      points.push_back(s.points[k] + u * (s.points[b] - s.points[k]));
      image.push_back(p);
    }
  }
  // A closed stroke wholly inside stays closed (its last sample is its first point again).
  if (s.closed && !cut && points.size() > 2) {
    points.pop_back();
    image.pop_back();
  }
  flush(s.closed && !cut);
  return out;
}

std::vector<std::vector<Vec2f>> clip_block(const std::vector<std::array<Vec2f, 3>>& cross, const SilhouetteMask& mask) {
  std::vector<std::vector<Vec2f>> out;
  std::vector<Vec2f> inner, outer;
  auto flush = [&] {
    if (inner.size() >= 2) {
      out.emplace_back(inner.begin(), inner.end());
      out.back().insert(out.back().end(), outer.rbegin(), outer.rend());
    }
    inner.clear();
    outer.clear();
  };
  // Where the way out from the line leaves the silhouette: the block is cut there.
  auto exit = [&](const Vec2f& base, const Vec2f& far) {
    const int steps = std::clamp(static_cast<int>(std::ceil(2.f * (far - base).norm() / mask.cell)), 1, 1 << 16);
    for (int t = 1; t <= steps; ++t)
      if (!mask.contains(base + (static_cast<float>(t) / static_cast<float>(steps)) * (far - base)))
        return (static_cast<float>(t) - 1.f) / static_cast<float>(steps);
    return 1.f;
  };
  for (std::size_t k = 0; k + 1 < cross.size(); ++k) {
    const auto& a = cross[k];
    const auto& b = cross[k + 1];
    const float span = std::max((b[1] - a[1]).norm(), (b[2] - a[2]).norm());
    const int steps = std::clamp(static_cast<int>(std::ceil(2.f * span / mask.cell)), 1, 1 << 16);
    for (int t = k == 0 ? 0 : 1; t <= steps; ++t) {
      const float u = static_cast<float>(t) / static_cast<float>(steps);
      const Vec2f base = a[0] + u * (b[0] - a[0]), in = a[1] + u * (b[1] - a[1]), out_pt = a[2] + u * (b[2] - a[2]);
      // Along base → out, the inner and outer boundary at their parameters; both cut at the exit.
      const Vec2f dir = out_pt - base;
      const float len2 = dir.squaredNorm();
      const float t_in = len2 > 0.f ? std::clamp((in - base).dot(dir) / len2, 0.f, 1.f) : 0.f;
      const float t_exit = mask.contains(base) ? exit(base, out_pt) : 0.f;
      if (t_exit <= t_in) {
        flush();
        continue;
      }
      inner.push_back(in);
      outer.push_back(base + t_exit * dir);
    }
  }
  flush();
  return out;
}

}  // namespace pcsketch::stylize::detail
