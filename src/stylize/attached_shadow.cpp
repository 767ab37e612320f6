// Attached-shadow hatching (beyond the paper): the visible surface facing away from the light, hatched in image space.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/angles.h"
#include "shadow_detail.h"

namespace pcsketch::stylize::detail {

namespace {

constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();

/// The nearest visible surface per image cell: the point whose disc the cell's viewing ray meets first.
struct ShadingGrid {
  int w = 0, h = 0;
  float cell = 1.f;
  std::vector<std::uint8_t> covered;  ///< w·h
  std::vector<float> depth;           ///< w·h, depth of the nearest disc along the cell's viewing ray
  std::vector<float> shade;           ///< w·h, n·l of the nearest disc, smoothed over covered neighbours
  /// Distance between samples along a hatch line, px: two per cell, so no cell is skipped.
  float step() const { return 0.5f * cell; }
};

/// Rasterises every point's oriented disc (as SurfaceScene sees it) with a z-buffer. Packing (depth bits, index)
/// into one 64-bit key and keeping the minimum with compare-and-swap gives the same grid for any thread count.
ShadingGrid splat(const ShadowInput& in, const ShadowOptions& o, const Vec3f& light) {
  const view::Camera& cam = in.camera;
  ShadingGrid g;
  g.cell = o.mask_cell_px;
  g.w = std::max(1, static_cast<int>(std::ceil(static_cast<float>(cam.width) / g.cell)));
  g.h = std::max(1, static_cast<int>(std::ceil(static_cast<float>(cam.height) / g.cell)));
  const std::size_t cells = static_cast<std::size_t>(g.w) * static_cast<std::size_t>(g.h);
  std::vector<std::atomic<std::uint64_t>> key(cells);
  // Cell loops run in parallel over rows of cells: each writes only its own cells.
  const auto each_row = [&](const auto& body) {
    tbb::parallel_for(tbb::blocked_range<int>(0, g.h), [&](const tbb::blocked_range<int>& r) {
      for (int y = r.begin(); y != r.end(); ++y) body(y);
    });
  };
  each_row([&](int y) {
    for (int x = 0; x < g.w; ++x) key[static_cast<std::size_t>(y) * g.w + x].store(kEmpty, std::memory_order_relaxed);
  });

  const std::size_t n = in.positions.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    // One row of cells at a time: its ray parameters and disc tests in a loop the compiler vectorises, then the
    // z-buffer updates of the cells inside the disc.
    std::vector<float> row_s(static_cast<std::size_t>(g.w));
    std::vector<std::int32_t> row_inside(static_cast<std::size_t>(g.w));
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3f& p = in.positions[i];
      const Vec3f& nrm = in.normals[i];
      const Vec3f uvd = cam.project(p);
      const float radius = o.splat_radius_factor * in.local_spacing[i];
      if (!(uvd.z() > 0.f) || !uvd.allFinite() || !nrm.allFinite() || !(radius > 0.f)) continue;
      const Vec3f ray = cam.ray_direction(p);
      const float nv = nrm.dot(ray);
      // Back-facing discs are never the visible side of an oriented surface; they are seen only through gaps
      // between front discs, where they would shade lit fronts. Edge-on discs cover no area.
      if (nv > -1e-4f) continue;
      const float upp = cam.units_per_pixel(uvd.z());
      const float r_px = radius / upp;
      // Clamped as floats first: a point near a perspective eye can project arbitrarily far.
      auto cell_of = [&](float px, int count) {
        return static_cast<int>(std::clamp(std::floor(px / g.cell), -1.f, static_cast<float>(count)));
      };
      const int x0 = std::max(0, cell_of(uvd.x() - r_px, g.w)), x1 = std::min(g.w - 1, cell_of(uvd.x() + r_px, g.w));
      const int y0 = std::max(0, cell_of(uvd.y() - r_px, g.h)), y1 = std::min(g.h - 1, cell_of(uvd.y() + r_px, g.h));
      const float ray_depth = ray.dot(cam.forward);
      // The cell's offset δ = upp·(du·right − dv·up) lies in the image plane at p's depth; its viewing ray meets the
      // disc's plane at δ + s·ray with s = −n·δ/(n·ray). Expanded into scalars (right ⟂ up) for the inner loop.
      const float n_right = nrm.dot(cam.right), n_up = nrm.dot(cam.up);
      const float ray_right = ray.dot(cam.right), ray_up = ray.dot(cam.up);
      const float r2 = radius * radius;
      const float cell = g.cell, u = uvd.x(), v = uvd.y(), depth = uvd.z();
      float* const s_of = row_s.data();
      std::int32_t* const inside = row_inside.data();
      for (int y = y0; y <= y1; ++y) {
        const float dv = ((static_cast<float>(y) + 0.5f) * cell - v) * upp;
        for (int x = x0; x <= x1; ++x) {
          const float du = ((static_cast<float>(x) + 0.5f) * cell - u) * upp;
          const float s = -(du * n_right - dv * n_up) / nv;
          s_of[x - x0] = s;
          inside[x - x0] = !(du * du + dv * dv + 2.f * s * (du * ray_right - dv * ray_up) + s * s > r2);
        }
        for (int x = x0; x <= x1; ++x) {
          if (!inside[x - x0]) continue;
          const float d = std::max(depth + s_of[x - x0] * ray_depth, 0.f);
          const std::uint64_t k = (static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(d)) << 32) | i;
          std::atomic<std::uint64_t>& slot = key[static_cast<std::size_t>(y) * g.w + x];
          std::uint64_t cur = slot.load(std::memory_order_relaxed);
          while (k < cur && !slot.compare_exchange_weak(cur, k, std::memory_order_relaxed)) {
          }
        }
      }
    }
  });

  g.covered.assign(cells, 0);
  g.depth.assign(cells, 0.f);
  std::vector<float> raw(cells, 0.f);
  each_row([&](int y) {
    for (std::size_t c = static_cast<std::size_t>(y) * g.w; c < static_cast<std::size_t>(y + 1) * g.w; ++c) {
      const std::uint64_t k = key[c].load(std::memory_order_relaxed);
      if (k == kEmpty) continue;
      const std::uint32_t i = static_cast<std::uint32_t>(k & 0xffffffffu);
      // Surfaces seen at a grazing angle are squeezed into thin strips where hatching reads as specks.
      if (-in.normals[i].dot(cam.ray_direction(in.positions[i])) < o.attached_min_facing) continue;
      g.covered[c] = 1;
      g.depth[c] = std::bit_cast<float>(static_cast<std::uint32_t>(k >> 32));
      raw[c] = in.normals[i].dot(light);
    }
  });
  // Normal noise makes the terminator ragged; a 3×3 mean over covered cells of similar depth smooths it.
  const float jump = o.depth_jump_factor * in.spacing;
  g.shade.assign(cells, 0.f);
  each_row([&](int y) {
    for (int x = 0; x < g.w; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * g.w + x;
      if (!g.covered[c]) continue;
      float sum = 0.f;
      int count = 0;
      for (int yy = std::max(0, y - 1); yy <= std::min(g.h - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(g.w - 1, x + 1); ++xx) {
          const std::size_t q = static_cast<std::size_t>(yy) * g.w + xx;
          if (g.covered[q] && std::abs(g.depth[q] - g.depth[c]) <= jump) {
            sum += raw[q];
            ++count;
          }
        }
      g.shade[c] = sum / static_cast<float>(count);
    }
  });
  return g;
}

/// A sample of the grid at an image position.
struct Sample {
  bool covered = false;
  float depth = 0.f;
  float shade = 0.f;
};

Sample sample(const ShadingGrid& g, const Vec2f& x) {
  Sample s;
  const int cx = static_cast<int>(std::floor(x.x() / g.cell)), cy = static_cast<int>(std::floor(x.y() / g.cell));
  if (cx < 0 || cy < 0 || cx >= g.w || cy >= g.h) return s;
  const std::size_t c = static_cast<std::size_t>(cy) * g.w + cx;
  if (!g.covered[c]) return s;
  s.covered = true;
  s.depth = g.depth[c];
  // Bilinear n·l over the covered cells among the four around x, so that hatch ends can be placed between cells.
  const float fx = x.x() / g.cell - 0.5f, fy = x.y() / g.cell - 0.5f;
  const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
  const float ax = fx - static_cast<float>(ix), ay = fy - static_cast<float>(iy);
  float sum = 0.f, weight = 0.f;
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const int xx = ix + dx, yy = iy + dy;
      if (xx < 0 || yy < 0 || xx >= g.w || yy >= g.h) continue;
      const std::size_t q = static_cast<std::size_t>(yy) * g.w + xx;
      if (!g.covered[q]) continue;
      const float wgt = (dx ? ax : 1.f - ax) * (dy ? ay : 1.f - ay);
      sum += wgt * g.shade[q];
      weight += wgt;
    }
  s.shade = weight > 0.f ? sum / weight : g.shade[c];
  return s;
}

/// The 3D point seen at image position x at depth `depth` (inverse of Camera::project).
Vec3f unproject(const view::Camera& cam, const Vec2f& x, float depth) {
  const float a = (x.x() - cam.principal.x()) / cam.scale, b = (cam.principal.y() - x.y()) / cam.scale;
  const float f = cam.projection == view::Projection::Perspective ? depth : 1.f;
  return cam.eye + depth * cam.forward + f * (a * cam.right + b * cam.up);
}

/// Hatch pieces along one image line x(t) = base + t·dir, t in [t0, t1], where the shade exceeds `threshold`.
void hatch_line(const ShadingGrid& g, const view::Camera& cam, const Vec2f& base, const Vec2f& dir, float t0, float t1,
                float threshold, float max_jump, const ShadowOptions& o, float grey, std::vector<Stroke>& out) {
  const float step = g.step();
  bool in_run = false;
  float run_start = 0.f, run_end = 0.f, start_depth = 0.f, end_depth = 0.f;
  Sample prev;
  float prev_t = t0;
  auto flush = [&] {
    if (in_run && run_end - run_start >= o.min_hatch_px) {
      const Vec2f a = base + run_start * dir, b = base + run_end * dir;
      out.push_back(hatch_stroke({unproject(cam, a, start_depth), unproject(cam, b, end_depth)}, {a, b}, false,
                                 o.attached_width_px, grey));
    }
    in_run = false;
  };
  const long samples = static_cast<long>(std::floor((t1 - t0) / step)) + 1;
  for (long k = 0; k < samples; ++k) {
    const float t = t0 + static_cast<float>(k) * step;
    const Sample s = sample(g, base + t * dir);
    const bool inside = s.covered && s.shade > threshold;
    if (in_run && inside && std::abs(s.depth - prev.depth) > max_jump) flush();  // another surface begins
    if (inside && !in_run) {
      in_run = true;
      run_start = t;
      // Entering across the terminator (both samples on the surface): place the start where n·l crosses.
      if (prev.covered && k > 0 && std::abs(s.depth - prev.depth) <= max_jump)
        run_start = prev_t + (threshold - prev.shade) / (s.shade - prev.shade) * (t - prev_t);
      start_depth = s.depth;
    }
    if (inside) {
      run_end = t;
      end_depth = s.depth;
    } else if (in_run) {
      if (s.covered && std::abs(s.depth - prev.depth) <= max_jump)
        run_end = prev_t + (threshold - prev.shade) / (s.shade - prev.shade) * (t - prev_t);
      flush();
    }
    prev = s;
    prev_t = t;
  }
  flush();
}

}  // namespace

std::vector<Stroke> attached_hatching(const ShadowInput& in, const ShadowOptions& o, const Vec3f& light) {
  std::vector<Stroke> out;
  if (in.positions.empty() || o.attached_levels.empty()) return out;
  const ShadingGrid g = splat(in, o, light);
  const view::Camera& cam = in.camera;
  // Hatch lines only need to cross the bounding box of the hatchable cells.
  int x_lo = g.w, x_hi = -1, y_lo = g.h, y_hi = -1;
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x)
      if (g.covered[static_cast<std::size_t>(y) * g.w + x]) {
        x_lo = std::min(x_lo, x);
        x_hi = std::max(x_hi, x);
        y_lo = std::min(y_lo, y);
        y_hi = std::max(y_hi, y);
      }
  if (x_hi < 0) return out;
  const Vec2f box_lo(static_cast<float>(x_lo) * g.cell, static_cast<float>(y_lo) * g.cell);
  const Vec2f box_hi(static_cast<float>(x_hi + 1) * g.cell, static_cast<float>(y_hi + 1) * g.cell);
  const float max_jump = o.depth_jump_factor * in.spacing;
  const std::size_t levels = o.attached_levels.size();
  for (std::size_t level = 0; level < levels; ++level) {
    const float theta =
        (o.hatch_angle_deg + static_cast<float>(level) * o.cross_angle_deg) * pcsketch::detail::kDegToRad;
    const Vec2f dir(std::cos(theta), -std::sin(theta));  // v points down: counter-clockwise as seen
    const Vec2f normal(-dir.y(), dir.x());
    // Lines m·x = j·spacing (anchored at the image origin, so they do not move with the box) crossing the box; the
    // parameter t runs along dir between the box's extremes.
    float o_lo = std::numeric_limits<float>::max(), o_hi = std::numeric_limits<float>::lowest();
    float t_lo = o_lo, t_hi = o_hi;
    for (const Vec2f& c : {box_lo, Vec2f(box_hi.x(), box_lo.y()), Vec2f(box_lo.x(), box_hi.y()), box_hi}) {
      o_lo = std::min(o_lo, normal.dot(c));
      o_hi = std::max(o_hi, normal.dot(c));
      t_lo = std::min(t_lo, dir.dot(c));
      t_hi = std::max(t_hi, dir.dot(c));
    }
    // Samples at multiples of the step, so the box does not shift them either.
    t_lo = std::floor(t_lo / g.step()) * g.step();
    const long j0 = static_cast<long>(std::ceil(o_lo / o.hatch_spacing_px));
    const long j1 = static_cast<long>(std::floor(o_hi / o.hatch_spacing_px));
    const std::size_t count = j1 >= j0 ? static_cast<std::size_t>(j1 - j0 + 1) : 0;
    const float grey = graded(o.attached_grey_light, o.attached_grey_dark, level, levels);
    std::vector<std::vector<Stroke>> per_line(count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k) {
        const Vec2f base = normal * (static_cast<float>(j0 + static_cast<long>(k)) * o.hatch_spacing_px);
        hatch_line(g, cam, base, dir, t_lo, t_hi, o.attached_levels[level], max_jump, o, grey, per_line[k]);
      }
    });
    for (auto& strokes : per_line)
      for (Stroke& s : strokes) out.push_back(std::move(s));
  }
  return out;
}

}  // namespace pcsketch::stylize::detail
