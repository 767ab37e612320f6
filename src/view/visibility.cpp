#include "pcsketch/view/visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/parallel_chunks.h"
#include "pcsketch/core/error.h"

namespace pcsketch::view {

namespace {

/// Whether p is seen: no disc between it (past the self offset) and the viewer, grazing discs near p skipped.
bool sees(const SurfaceScene& scene, const Camera& camera, const Vec3f& p, float offset, float grazing_range,
          const VisibilityOptions& o) {
  const Vec3f to_viewer = -camera.ray_direction(p);
  float t_far = std::numeric_limits<float>::infinity();
  if (camera.projection == Projection::Perspective) {
    const float depth = (p - camera.eye).dot(camera.forward);
    if (!(depth > 0)) return false;
    t_far = (camera.eye - p).norm();
  }
  if (o.grazing_cos <= 0) return !scene.occluded(p, to_viewer, offset, t_far);
  float t_near = offset;
  // Bounded: past a few grazing discs the ray is running along the surface, which then counts as seen.
  for (int step = 0; step < 32; ++step) {
    const auto hit = scene.intersect(p, to_viewer, t_near, t_far);
    if (!hit) return true;
    if (hit->t > grazing_range || std::abs(hit->normal.dot(to_viewer)) >= o.grazing_cos) return false;
    t_near = std::nextafter(hit->t, std::numeric_limits<float>::infinity()) + 1e-3f * offset;
  }
  return true;
}

/// Where each vertex of `line` casts its ray from, and its length unit (h, or for a contour its source disc's
/// radius where that is larger; VisibilityOptions::offset_from_local_spacing): the vertex, lifted to its source
/// point's tangent plane when it lies below it (VisibilityOptions::lift_to_source_plane).
struct RayOrigins {
  std::vector<Vec3f> points;
  std::vector<float> unit;
};
RayOrigins ray_origins(const Polyline& line, const SurfaceScene& scene, float spacing, const VisibilityOptions& o) {
  RayOrigins out{line.points, std::vector<float>(line.points.size(), spacing)};
  if (line.point_index.size() != line.points.size()) return out;
  for (std::size_t i = 0; i < out.points.size(); ++i) {
    if (line.point_index[i] >= scene.size()) continue;
    const SurfaceDisc disc = scene.disc(line.point_index[i]);
    if (!(disc.radius > 0)) continue;
    if (o.offset_from_local_spacing && line.kind == LineKind::Contour) out.unit[i] = std::max(spacing, disc.radius);
    const float below = (disc.centre - out.points[i]).dot(disc.normal);
    if (o.lift_to_source_plane && below > 0) out.points[i] += below * disc.normal;
  }
  return out;
}

/// Majority vote over a centred window (wrapping on closed lines, shrinking at open ends).
std::vector<std::uint8_t> smooth_flags(const std::vector<std::uint8_t>& raw, std::size_t window, bool closed) {
  const std::size_t n = raw.size();
  if (window <= 1 || n < 3) return raw;
  const auto half = static_cast<std::ptrdiff_t>(window / 2);
  std::vector<std::uint8_t> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    int seen = 0, total = 0;
    for (std::ptrdiff_t o = -half; o <= half; ++o) {
      auto j = static_cast<std::ptrdiff_t>(i) + o;
      if (closed) {
        j = (j % static_cast<std::ptrdiff_t>(n) + static_cast<std::ptrdiff_t>(n)) % static_cast<std::ptrdiff_t>(n);
      } else if (j < 0 || j >= static_cast<std::ptrdiff_t>(n)) {
        continue;
      }
      seen += raw[static_cast<std::size_t>(j)];
      ++total;
    }
    out[i] = static_cast<std::uint8_t>(2 * seen > total ? 1 : (2 * seen < total ? 0 : raw[i]));
  }
  return out;
}

void build_runs(ViewLine& vl, const Camera& camera) {
  const Polyline& line = vl.line;
  const std::size_t n = line.points.size();
  if (n == 0) return;
  const std::size_t segments = line.closed && n > 2 ? n : n - 1;
  auto add = [&](LineRun& run, const Vec3f& p, float param) {
    run.points.push_back(p);
    run.projected.push_back(camera.project(p));
    run.param.push_back(param);
  };
  LineRun run;
  run.visible = vl.visible[0] != 0;
  add(run, line.points[0], 0.f);
  for (std::size_t s = 0; s < segments; ++s) {
    const std::size_t b = (s + 1) % n;
    const bool vb = vl.visible[b] != 0;
    if (vb != run.visible) {
      const float f = vl.split[s];
      const Vec3f mid = line.points[s] + f * (line.points[b] - line.points[s]);
      add(run, mid, static_cast<float>(s) + f);
      vl.runs.push_back(std::move(run));
      run = LineRun{};
      run.visible = vb;
      add(run, mid, static_cast<float>(s) + f);
    }
    add(run, line.points[b], static_cast<float>(s + 1));
  }
  vl.runs.push_back(std::move(run));
}

}  // namespace

ViewLine seen_line(const Polyline& line, const Camera& camera) {
  ViewLine vl;
  vl.line = line;
  const std::size_t n = line.points.size();
  vl.projected.resize(n);
  for (std::size_t i = 0; i < n; ++i) vl.projected[i] = camera.project(line.points[i]);
  vl.visible.assign(n, 1);
  vl.split.assign(n == 0 ? 0 : (line.closed && n > 2 ? n : n - 1), 0.5f);
  build_runs(vl, camera);
  return vl;
}

std::vector<ViewLine> line_visibility(const std::vector<Polyline>& lines, const SurfaceScene& scene,
                                      const Camera& camera, float spacing, const VisibilityOptions& o) {
  if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("visibility: the mean spacing h must be positive");
  if (o.smoothing_window % 2 == 0) throw Error("visibility: the smoothing window must be odd");
  std::vector<ViewLine> out(lines.size());
  // Lines vary from a handful to thousands of vertices; a grain of one line keeps both cores busy.
  pcsketch::detail::parallel_chunks(lines.size(), o.progress, "visibility", [&](std::size_t begin, std::size_t end) {
    for (std::size_t l = begin; l != end; ++l) {
      ViewLine& vl = out[l];
      vl.line = lines[l];
      const std::size_t n = vl.line.points.size();
      vl.projected.resize(n);
      std::vector<std::uint8_t> raw(n);
      const RayOrigins origins = ray_origins(vl.line, scene, spacing, o);
      const auto seen_from = [&](const Vec3f& p, float unit) {
        return sees(scene, camera, p, o.self_offset_factor * unit, o.grazing_range_factor * spacing, o);
      };
      for (std::size_t i = 0; i < n; ++i) {
        vl.projected[i] = camera.project(vl.line.points[i]);
        raw[i] = seen_from(origins.points[i], origins.unit[i]) ? 1 : 0;
      }
      vl.visible = smooth_flags(raw, o.smoothing_window, vl.line.closed);
      const std::size_t segments = n == 0 ? 0 : (vl.line.closed && n > 2 ? n : n - 1);
      vl.split.assign(segments, 0.5f);
      for (std::size_t s = 0; s < segments; ++s) {
        const std::size_t b = (s + 1) % n;
        if (vl.visible[s] == vl.visible[b]) continue;
        // Bisect for the change point (between the ray origins); the end with the smoothed flag of `s` is kept at lo.
        float lo = 0.f, hi = 1.f;
        const Vec3f pa = origins.points[s], pb = origins.points[b];
        const float ua = origins.unit[s], ub = origins.unit[b];
        for (int it = 0; it < o.transition_refinement; ++it) {
          const float mid = 0.5f * (lo + hi);
          const bool v = seen_from(pa + mid * (pb - pa), ua + mid * (ub - ua));
          (v == (vl.visible[s] != 0) ? lo : hi) = mid;
        }
        vl.split[s] = 0.5f * (lo + hi);
      }
      build_runs(vl, camera);
    }
  }, 1);
  return out;
}

}  // namespace pcsketch::view
