#include "pcsketch/stylize/shadow.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "core/angles.h"
#include "pcsketch/core/error.h"
#include "shadow_detail.h"

namespace pcsketch::stylize {

namespace {

using pcsketch::detail::kDegToRad;

/// A maximal chain of vertex indices whose consecutive segments all passed a test; closed when it is the whole loop.
struct Chain {
  std::vector<std::size_t> vertices;
  bool closed = false;
};

/// Splits the segments of a polyline of `n` vertices (segment s joins s and s + 1 mod n) into chains of passing
/// segments. A closed line whose segments all pass is one closed chain.
template <class SegmentOk>
std::vector<Chain> chains(std::size_t n, bool closed, SegmentOk ok) {
  std::vector<Chain> out;
  if (n < 2) return out;
  const std::size_t segs = closed ? n : n - 1;
  std::size_t start = 0;
  if (closed) {
    std::size_t first_bad = segs;
    for (std::size_t s = 0; s < segs && first_bad == segs; ++s)
      if (!ok(s)) first_bad = s;
    if (first_bad == segs) {
      Chain c{{}, true};
      for (std::size_t i = 0; i < n; ++i) c.vertices.push_back(i);
      out.push_back(std::move(c));
      return out;
    }
    start = first_bad + 1;
  }
  Chain cur;
  for (std::size_t k = 0; k < segs; ++k) {
    const std::size_t s = (start + k) % n;
    if (ok(s)) {
      if (cur.vertices.empty()) cur.vertices.push_back(s);
      cur.vertices.push_back((s + 1) % n);
    } else if (!cur.vertices.empty()) {
      out.push_back(std::move(cur));
      cur = {};
    }
  }
  if (!cur.vertices.empty()) out.push_back(std::move(cur));
  return out;
}

/// The block of chain `c` between hatch lines j − 1 and j (`corner(i, k)`: the image of vertex i's point on hatch
/// line k, line 0 being the feature line), appended to `out`.
template <class Corner>
void add_block(const Chain& c, std::size_t j, Corner corner, float grey, const detail::SilhouetteMask* mask,
               std::vector<ShadeRegion>& out) {
  if (mask) {
    // Linear between vertices, a block could cross a gap in the silhouette: it is cut at half-cell samples.
    std::vector<std::array<Vec2f, 3>> cross;
    for (std::size_t i : c.vertices) cross.push_back({corner(i, 0), corner(i, j - 1), corner(i, j)});
    if (c.closed) cross.push_back(cross.front());
    for (std::vector<Vec2f>& polygon : detail::clip_block(cross, *mask)) out.push_back({std::move(polygon), grey});
    return;
  }
  // Inner boundary forward, outer boundary back: one polygon per block (a closed chain is an annulus with a
  // zero-width seam, which fills correctly).
  ShadeRegion r;
  r.grey = grey;
  for (std::size_t i : c.vertices) r.polygon.push_back(corner(i, j - 1));
  if (c.closed) r.polygon.push_back(corner(c.vertices.front(), j - 1));
  if (c.closed) r.polygon.push_back(corner(c.vertices.front(), j));
  for (auto it = c.vertices.rbegin(); it != c.vertices.rend(); ++it) r.polygon.push_back(corner(*it, j));
  out.push_back(std::move(r));
}

/// The paper's cast shadow of one line: hatch strokes per k and graded blocks.
struct LineShadow {
  std::vector<Stroke> strokes;
  std::vector<ShadeRegion> regions;
  std::size_t candidates = 0, cast = 0;
};

LineShadow line_shadow(const ShadowInput& in, const Polyline& line, const std::vector<std::uint8_t>& flags,
                       const std::vector<float>& ts, const ShadowOptions& o, const Vec3f& light,
                       const detail::SilhouetteMask* mask) {
  LineShadow out;
  const std::size_t n = line.size();
  const float h = in.spacing;
  const view::Camera& cam = in.camera;
  std::vector<std::uint8_t> casts(n, 0);
  std::vector<Vec3f> offset(n, Vec3f::Zero());  // n = p' − p of eq. 12
  for (std::size_t i = 0; i < n; ++i) {
    if (!flags.empty() && flags[i] == 0) continue;
    ++out.candidates;
    const Vec3f& p = line.points[i];
    const auto hit = in.scene.intersect(p, light, o.ray_offset_factor * h, o.max_cast_factor * h);
    // A hit on a disc facing away from the light was reached from inside the object: p lies on the lit side.
    if (!hit || !(in.normals[hit->point].dot(light) < 0.f)) continue;
    casts[i] = 1;
    offset[i] = hit->t * light;
    ++out.cast;
  }
  if (out.cast == 0) return out;

  // Hatch point of vertex i on hatch line j (j = 0 is the line itself, t = 0).
  const std::size_t m = ts.size();
  auto point = [&](std::size_t i, std::size_t j) -> Vec3f {
    return j == 0 ? line.points[i] : Vec3f(line.points[i] + ts[j - 1] * offset[i]);
  };
  std::vector<std::uint8_t> valid(n * (m + 1), 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!casts[i]) continue;
    valid[i * (m + 1)] = 1;
    for (std::size_t j = 1; j <= m; ++j) {
      const Vec3f q = point(i, j);
      const Vec3f to_viewer = -cam.ray_direction(q);
      const float far = cam.projection == view::Projection::Perspective ? (cam.eye - q).norm()
                                                                        : std::numeric_limits<float>::infinity();
      const float offset_to_viewer = o.visibility_offset_factor * h;
      // The surface-behind test (from just in front of q, so that a point on the surface finds its own disc) only
      // for points the camera sees: a second ray per hidden point would be wasted.
      valid[i * (m + 1) + j] =
          !in.scene.occluded(q, to_viewer, offset_to_viewer, far) &&
          (!o.clip_to_surface || in.scene.occluded(q + offset_to_viewer * to_viewer, -to_viewer, 0.f,
                                                   std::numeric_limits<float>::infinity()));
    }
  }
  auto ok = [&](std::size_t i, std::size_t j) { return valid[i * (m + 1) + j] != 0; };
  auto jump = [&](std::size_t s) {
    const std::size_t a = s, b = (s + 1) % n;
    const Vec3f pa = line.points[a] + offset[a], pb = line.points[b] + offset[b];
    return (pa - pb).norm() > o.max_jump_factor * std::max(h, (line.points[a] - line.points[b]).norm());
  };
  auto image = [&](const Vec3f& q) -> Vec2f { return cam.project(q).head<2>(); };

  for (std::size_t j = 1; j <= m; ++j) {
    const float grey = detail::graded(o.cast_grey_near, o.cast_grey_far, j - 1, m);
    for (const Chain& c :
         chains(n, line.closed, [&](std::size_t s) { return ok(s, j) && ok((s + 1) % n, j) && !jump(s); })) {
      std::vector<Vec3f> pts;
      std::vector<Vec2f> img;
      for (std::size_t i : c.vertices) {
        pts.push_back(point(i, j));
        img.push_back(image(pts.back()));
      }
      out.strokes.push_back(
          detail::hatch_stroke(std::move(pts), std::move(img), c.closed, o.cast_hatch_width_px, grey));
    }
  }
  if (!o.shade_blocks) return out;
  for (std::size_t j = 1; j <= m; ++j) {
    const float grey = detail::graded(o.block_grey_near, o.block_grey_far, j - 1, m);
    for (const Chain& c : chains(n, line.closed, [&](std::size_t s) {
           const std::size_t b = (s + 1) % n;
           return ok(s, j - 1) && ok(b, j - 1) && ok(s, j) && ok(b, j) && !jump(s);
         })) {
      add_block(c, j, [&](std::size_t i, std::size_t k) { return image(point(i, k)); }, grey, mask, out.regions);
    }
  }
  return out;
}

void check(const ShadowInput& in, const ShadowOptions& o) {
  const std::size_t n = in.positions.size();
  if (in.normals.size() != n || in.local_spacing.size() != n)
    throw Error("stylize/shadow: positions, normals and local spacing must have one entry per point (got " +
                std::to_string(n) + ", " + std::to_string(in.normals.size()) + ", " +
                std::to_string(in.local_spacing.size()) + ")");
  if (!in.visible.empty() && in.visible.size() != in.lines.size())
    throw Error("stylize/shadow: visibility given for " + std::to_string(in.visible.size()) + " lines, expected " +
                std::to_string(in.lines.size()));
  for (std::size_t i = 0; i < in.visible.size(); ++i)
    if (!in.visible[i].empty() && in.visible[i].size() != in.lines[i].size())
      throw Error("stylize/shadow: line " + std::to_string(i) + " has " + std::to_string(in.lines[i].size()) +
                  " points but " + std::to_string(in.visible[i].size()) + " visibility flags");
  if (!(o.hatch_spacing_px > 0.f) || !(o.mask_cell_px > 0.f) || !(o.d > 0.f))
    throw Error("stylize/shadow: hatch spacing, mask cell and d must be positive");
}

}  // namespace

namespace detail {

Stroke hatch_stroke(std::vector<Vec3f> points, std::vector<Vec2f> image_points, bool closed, float width, float grey) {
  Stroke s;
  s.kind = LineKind::Hatch;
  s.visible = true;
  s.closed = closed;
  s.points = std::move(points);
  s.image_points = std::move(image_points);
  s.widths.assign(s.points.size(), width);
  s.half_widths.assign(2 * s.segments(), width);
  s.grey = grey;
  return s;
}

float graded(float a, float b, std::size_t i, std::size_t count) {
  if (count < 2) return a;
  return a + (b - a) * static_cast<float>(i) / static_cast<float>(count - 1);
}

}  // namespace detail

Vec3f light_direction(const LightOptions& light, const view::Camera& camera) {
  Vec3f d;
  if (light.direction) {
    d = *light.direction;
    if (!d.allFinite() || !(d.norm() > 0.f))
      throw Error("stylize/light: the light direction must be a non-zero vector");
  } else {
    const float e = light.elevation_deg * kDegToRad, a = light.azimuth_deg * kDegToRad;
    d = Vec3f(-std::cos(e) * std::cos(a), -std::cos(e) * std::sin(a), std::sin(e));
  }
  d.normalize();
  // The paper's camera has right = −x, up = y, forward = z: reading d in that frame keeps the default unchanged.
  if (light.follow_camera) d = (-d.x() * camera.right + d.y() * camera.up + d.z() * camera.forward).normalized();
  return d;
}

ShadowResult shadow_hatching(const ShadowInput& in, const ShadowOptions& o) {
  ShadowResult result;
  result.light = light_direction(o.light, in.camera);
  if (o.mode == ShadowMode::None) return result;
  check(in, o);
  // Reported between the steps: each is a parallel loop of a fraction of a second on millions of points.
  const ProgressReporter report(o.progress, "shadows");
  report(0.0);
  if (in.positions.empty() || !(in.spacing > 0.f) || !std::isfinite(in.spacing)) {
    // A degenerate cloud (no points, or all coincident) has no surface to shade: an unshaded drawing, not an error.
    result.warnings.push_back("shadow: no shading, the cloud has no point spacing (empty or degenerate cloud)");
    return result;
  }

  // Shading stays on the object: with clip_to_surface every block and hatch stroke is cut to the silhouette.
  const std::optional<detail::SilhouetteMask> mask =
      o.clip_to_surface ? std::optional(detail::silhouette_mask(in, o)) : std::nullopt;
  const detail::SilhouetteMask* const clip = mask ? &*mask : nullptr;
  report(0.25);
  if (o.mode == ShadowMode::Paper || o.mode == ShadowMode::Both) {
    std::vector<float> ts;
    for (float k : o.k_set)
      if (k > 0.f && k * o.d <= 1.f + 1e-6f) ts.push_back(std::min(k * o.d, 1.f));
    std::sort(ts.begin(), ts.end());
    ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
    std::vector<LineShadow> per_line(in.lines.size());
    static const std::vector<std::uint8_t> kAllVisible;
    if (!ts.empty()) {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, in.lines.size()), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
              const Polyline& l = in.lines[i];
              const bool casts = l.kind == LineKind::Ridge || (l.kind == LineKind::Valley && o.cast_from_valleys);
              if (!casts || l.size() < 2) continue;
              per_line[i] =
                  line_shadow(in, l, in.visible.empty() ? kAllVisible : in.visible[i], ts, o, result.light, clip);
            }
          });
    }
    for (LineShadow& s : per_line) {
      result.casting_candidates += s.candidates;
      result.cast_vertices += s.cast;
      for (Stroke& st : s.strokes) result.strokes.push_back(std::move(st));
      for (ShadeRegion& r : s.regions) result.regions.push_back(std::move(r));
    }
  }
  report(0.5);
  if (o.mode == ShadowMode::Attached || o.mode == ShadowMode::Both) {
    std::vector<Stroke> hatch = detail::attached_hatching(in, o, result.light);
    for (Stroke& s : hatch) result.strokes.push_back(std::move(s));
  }
  if (clip) {
    std::vector<Stroke> clipped;
    for (const Stroke& s : result.strokes)
      for (Stroke& piece : detail::clip_stroke(s, *clip)) clipped.push_back(std::move(piece));
    result.strokes = std::move(clipped);
  }
  report(1.0);
  return result;
}

}  // namespace pcsketch::stylize
