// Shading stays on the object: the silhouette of the view as a mask, and the clipping of hatch strokes and shade
// blocks against it.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "shadow_detail.h"

namespace pcsketch::stylize::detail {

bool SilhouetteMask::contains(const Vec2f& p) const {
  if (!p.allFinite()) return false;
  const float x = std::floor(p.x() / cell), y = std::floor(p.y() / cell);
  if (x < 0.f || y < 0.f || x >= static_cast<float>(w) || y >= static_cast<float>(h)) return false;
  return inside[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] != 0;
}

namespace {

/// Samples over `length` px at most half a cell apart (capped: a degenerate far-away point must not hang the loop).
int half_cell_steps(float length, const SilhouetteMask& mask) {
  const float steps = std::ceil(2.f * length / mask.cell);
  return steps >= 1.f ? static_cast<int>(std::min(steps, 65536.f)) : 1;  // NaN too gives 1
}

/// Keeps the cells with no outside cell (or image border) within `radius` cells. The outside cell nearest to an
/// inside one always touches an inside cell, so only those are stamped: the cost goes with the outline's length,
/// not the object's area.
void erode(SilhouetteMask& m, float radius) {
  std::vector<std::pair<int, int>> disc;
  const int reach = static_cast<int>(std::floor(radius));
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx)
      if (static_cast<float>(dx * dx + dy * dy) <= radius * radius) disc.emplace_back(dx, dy);
  auto inside = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < m.w && y < m.h && m.inside[static_cast<std::size_t>(y) * m.w + x];
  };
  std::vector<std::uint8_t> kept = m.inside;
  for (int y = -1; y <= m.h; ++y)
    for (int x = -1; x <= m.w; ++x) {
      if (inside(x, y) || !(inside(x - 1, y) || inside(x + 1, y) || inside(x, y - 1) || inside(x, y + 1))) continue;
      for (const auto& [dx, dy] : disc)
        if (inside(x + dx, y + dy)) kept[static_cast<std::size_t>(y + dy) * m.w + x + dx] = 0;
    }
  m.inside = std::move(kept);
}

}  // namespace

SilhouetteMask silhouette_mask(const ShadowInput& in, const ShadowOptions& o) {
  const view::Camera& cam = in.camera;
  SilhouetteMask m;
  m.cell = o.mask_cell_px;
  m.w = std::max(1, static_cast<int>(std::ceil(static_cast<float>(cam.width) / m.cell)));
  m.h = std::max(1, static_cast<int>(std::ceil(static_cast<float>(cam.height) / m.cell)));
  m.inside.assign(static_cast<std::size_t>(m.w) * static_cast<std::size_t>(m.h), 0);
  // Every point as a round splat of its disc radius, whichever way it faces, then eroded (a closing): gaps between
  // points are filled, and the discs' overhang past the outermost points is taken back, so the mask ends at the
  // outline the contours trace. The erosion takes the 90th percentile of the radii: with the median, the larger discs
  // of a cloud's sparse parts kept part of their overhang (the fandisk's vertices: 120 shading pixels over 1.5 px past
  // its mesh, 19 with the 90th percentile). In parallel: splats only ever set cells, so the mask is the same for any
  // thread count (relaxed atomic stores, since neighbouring splats write the same cells).
  std::vector<float> radii(in.positions.size(), 0.f);
  const tbb::blocked_range<std::size_t> points(0, in.positions.size());
  tbb::parallel_for(points, [&](const tbb::blocked_range<std::size_t>& range) {
    auto set = [&](int x, int y) {
      std::atomic_ref<std::uint8_t> cell(m.inside[static_cast<std::size_t>(y) * m.w + x]);
      cell.store(1, std::memory_order_relaxed);
    };
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Vec3f uvd = cam.project(in.positions[i]);
      if (!(uvd.z() > 0.f) || !uvd.allFinite()) continue;
      const float r = o.splat_radius_factor * in.local_spacing[i] / cam.units_per_pixel(uvd.z()) / m.cell;
      if (!(r > 0.f) || !std::isfinite(r)) continue;
      radii[i] = r;
      const float cx = uvd.x() / m.cell, cy = uvd.y() / m.cell;
      if (cx >= 0.f && cy >= 0.f && cx < static_cast<float>(m.w) && cy < static_cast<float>(m.h))
        set(static_cast<int>(cx), static_cast<int>(cy));  // a disc smaller than a cell
      const int y0 = std::max(0, static_cast<int>(std::floor(std::max(cy - r, -1.f))));
      const int y1 = std::min(m.h - 1, static_cast<int>(std::floor(std::min(cy + r, static_cast<float>(m.h)))));
      const int x0 = std::max(0, static_cast<int>(std::floor(std::max(cx - r, -1.f))));
      const int x1 = std::min(m.w - 1, static_cast<int>(std::floor(std::min(cx + r, static_cast<float>(m.w)))));
      // A cell is in when its centre lies on the disc: the mask then reaches at most half a cell's diagonal past it.
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const float dx = static_cast<float>(x) + 0.5f - cx, dy = static_cast<float>(y) + 0.5f - cy;
          if (dx * dx + dy * dy <= r * r) set(x, y);
        }
    }
  });
  std::erase(radii, 0.f);
  if (radii.empty()) return m;
  const std::size_t high = radii.size() * 9 / 10;
  std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(high), radii.end());
  erode(m, radii[high]);
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
  // The stroke's own vertices are kept; where it leaves or re-enters the mask (tested every half cell) it is cut
  // at the last and first sample inside.
  bool was_inside = n > 0 && mask.contains(s.image_points[0]);
  if (was_inside) {
    points.push_back(s.points[0]);
    image.push_back(s.image_points[0]);
  }
  for (std::size_t k = 0; k < s.segments(); ++k) {
    const std::size_t b = (k + 1) % n;
    const Vec2f &ia = s.image_points[k], &ib = s.image_points[b];
    const int steps = half_cell_steps((ib - ia).norm(), mask);
    auto at = [&](int t) {
      const float u = static_cast<float>(t) / static_cast<float>(steps);
      return std::pair<Vec3f, Vec2f>(s.points[k] + u * (s.points[b] - s.points[k]), ia + u * (ib - ia));
    };
    for (int t = 1; t <= steps; ++t) {
      const auto [point, pixel] = at(t);
      const bool inside = mask.contains(pixel);
      if (inside && (!was_inside || t == steps)) {
        points.push_back(point);
        image.push_back(pixel);
      } else if (!inside && was_inside) {
        if (t > 1) {
          const auto [last_point, last_pixel] = at(t - 1);
          points.push_back(last_point);
          image.push_back(last_pixel);
        }
        cut = true;
        flush(false);
      }
      was_inside = inside;
    }
  }
  // A closed stroke wholly inside stays closed (its last point is its first again).
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
    const int steps = half_cell_steps((far - base).norm(), mask);
    for (int t = 1; t <= steps; ++t)
      if (!mask.contains(base + (static_cast<float>(t) / static_cast<float>(steps)) * (far - base)))
        return (static_cast<float>(t) - 1.f) / static_cast<float>(steps);
    return 1.f;
  };
  for (std::size_t k = 0; k + 1 < cross.size(); ++k) {
    const auto& a = cross[k];
    const auto& b = cross[k + 1];
    const float span = std::max((b[1] - a[1]).norm(), (b[2] - a[2]).norm());
    const int steps = half_cell_steps(span, mask);
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
