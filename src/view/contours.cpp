#include "pcsketch/view/contours.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <span>

#include "contour_walk.h"
#include "core/angles.h"
#include "core/nth_value.h"
#include "core/progress.h"
#include "depth_edges.h"
#include "interior_contours.h"
#include "outline_bridges.h"
#include "outline_points.h"
#include "pcsketch/core/error.h"
#include "point_grid.h"
#include "rim_bending.h"

namespace pcsketch::view {

namespace {

using pcsketch::detail::kDegToRad;

using detail::polyline_length;
using detail::Walker;

/// The unit vector pointing to the empty side of heading d: side = +1 on the right of d in (u, v), −1 on the left.
Vec2f side_of(const Vec2f& d, float side) { return side * Vec2f(d.y(), -d.x()); }

/// The heading a walk starts with so that the empty direction `outward` lies on its `side`.
Vec2f heading_for(const Vec2f& outward, float side) { return side * Vec2f(-outward.y(), outward.x()); }

/// The next outline point from `cur` along `d` with the empty side on `side`, or -1. `closing` is the seed when it
/// may close the line (else cur itself, which is never a candidate).
std::int64_t next_outline_point(Walker<2>& walker, float side, float max_turn, std::uint32_t cur, const Vec2f& d,
                                float radius, std::uint32_t closing) {
  const ContourOptions& o = walker.options;
  const Vec2f p = walker.pts[cur];
  const Vec2f s = side_of(d, side);
  const float z_max = o.z_max_factor * walker.scale[cur];
  std::int64_t best = -1;
  float best_score = 0, best_dist = 0;
  bool closes = false;
  walker.grid.for_each_within(p, radius, [&](std::uint32_t j, float d2) {
    if (j == cur || (walker.used[j] && j != closing)) return;
    const Vec2f c = walker.pts[j] - p;
    const float dist = std::sqrt(d2);
    if (dist <= 1e-6f * radius) {
      walker.used[j] = 1;  // a duplicate of the current point
      return;
    }
    const float along = c.dot(d), lateral = c.dot(s);
    const float angle = std::atan2(lateral, along);
    if (std::abs(angle) > max_turn) return;
    if (j == closing) {
      closes = true;
      return;
    }
    float score;
    if (o.connection == OutlineConnection::Outermost) {
      score = angle;
    } else {
      if (along <= 0 || std::abs(lateral) >= z_max) return;
      score = -dist;
    }
    if (best < 0 || score > best_score || (score == best_score && dist < best_dist)) {
      best = j;
      best_score = score;
      best_dist = dist;
    }
  });
  return closes ? static_cast<std::int64_t>(closing) : best;
}

/// The points in order of u, then v, then index: the leftmost point is on the outer outline.
std::vector<std::uint32_t> left_to_right(const std::vector<Vec2f>& pts) {
  std::vector<std::uint32_t> order(pts.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (pts[a].x() != pts[b].x()) return pts[a].x() < pts[b].x();
    if (pts[a].y() != pts[b].y()) return pts[a].y() < pts[b].y();
    return a < b;
  });
  return order;
}

/// The walked chain of boundary points as an outline line of cloud points; nothing when it has under 3 points or is
/// shorter in the image than min_length_factor times its mean spacing.
std::optional<Polyline> outline_line(const Walker<2>& walker, const std::vector<std::uint32_t>& chain, bool closed,
                                     const ContourPoints& cp, const std::vector<Vec3f>& positions) {
  Polyline line;
  line.kind = LineKind::Contour;
  line.closed = closed;
  std::vector<Vec3f> image(chain.size());
  float scale_sum = 0;
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const std::uint32_t point = cp.boundary[chain[i]];
    line.points.push_back(positions[point]);
    line.point_index.push_back(point);
    image[i] = Vec3f(walker.pts[chain[i]].x(), walker.pts[chain[i]].y(), 0.f);
    scale_sum += walker.scale[chain[i]];
  }
  const float min_length = walker.options.min_length_factor * scale_sum / static_cast<float>(chain.size());
  if (chain.size() >= 3 && polyline_length(image, closed) >= min_length) return line;
  return std::nullopt;
}

/// Chains the outline's boundary points in the image plane (forward with the empty side on the right, then
/// backward from the seed when the outline did not close).
std::vector<Polyline> trace_outline(const ContourPoints& cp, const std::vector<Vec3f>& positions,
                                    const ContourOptions& o, pcsketch::detail::ProgressSteps& steps) {
  const std::size_t nb = cp.boundary.size();
  std::vector<Vec2f> pts(nb);
  std::vector<float> scale(nb);
  double mean_scale = 0;
  for (std::size_t b = 0; b < nb; ++b) {
    pts[b] = cp.projected[cp.boundary[b]].head<2>();
    scale[b] = cp.spacing_px[cp.boundary[b]];
    mean_scale += scale[b];
  }
  if (nb == 0) return {};
  mean_scale /= static_cast<double>(nb);
  const detail::PointGrid<2> grid(pts, o.trace_radius_factor * static_cast<float>(mean_scale));
  Walker<2> walker{pts, grid, scale, o, std::vector<char>(nb, 0)};
  const float max_turn = o.max_turn_deg * kDegToRad;
  auto chooser = [&walker, max_turn](float side) {
    return [&walker, max_turn, side](std::uint32_t cur, const Vec2f& d, float radius,
                                     std::uint32_t closing) -> std::int64_t {
      return next_outline_point(walker, side, max_turn, cur, d, radius, closing);
    };
  };

  // Seeds from the left, as the paper does.
  const std::vector<std::uint32_t> seeds = left_to_right(pts);
  std::vector<Polyline> lines;
  for (std::size_t s = 0; s < nb; ++s) {
    steps.at(s);
    const std::uint32_t seed = seeds[s];
    if (walker.used[seed]) continue;
    walker.used[seed] = 1;
    const auto [chain, closed] = walker.grow_both_ways(seed, heading_for(cp.outward[seed], +1.f), chooser(+1.f),
                                                       heading_for(cp.outward[seed], -1.f), chooser(-1.f));
    if (std::optional<Polyline> line = outline_line(walker, chain, closed, cp, positions))
      lines.push_back(std::move(*line));
  }
  return lines;
}

/// Each point's spacing unit for the outline: h, or where the cloud is sparser the local spacing (see
/// ContourOptions::adaptive_spacing).
std::vector<float> spacing_units(const neighbourhood::Neighbourhoods& neighbourhoods, float h, std::size_t n,
                                 bool adaptive) {
  if (!adaptive || neighbourhoods.size() != n || neighbourhoods.k == 0) return std::vector<float>(n, h);
  const std::size_t k = neighbourhoods.k;
  std::vector<float> far(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) far[i] = neighbourhoods.distances_of(i)[k - 1];
  });
  const float median = pcsketch::detail::nth_value(far, n / 2);
  if (!(median > 0)) return std::vector<float>(n, h);
  // Averaged over the neighbours: one point's k-th distance scatters by about 30% on a random sampling.
  const float to_h = h / median;
  std::vector<float> unit(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      float sum = far[i];
      for (const std::uint32_t j : neighbourhoods.of(i)) sum += far[j];
      unit[i] = std::max(h, to_h * sum / static_cast<float>(k + 1));
    }
  });
  return unit;
}

/// The interior rim samples (see ContourPoints::rim) and the points they were made from, into `cp`; on a denoised
/// cloud whether each bends too.
void add_rim_samples(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                     const neighbourhood::Neighbourhoods& neighbourhoods, const Camera& camera, const ContourOptions& o,
                     float normal_noise, bool denoised, ContourPoints& cp) {
  const std::size_t n = positions.size();
  // f = n·v < 0 faces the viewer; a rim sample sits at the zero crossings between a point and its neighbours
  // facing the other way (averaged), i.e. on the occluding contour generator. Points on both sides make samples:
  // one side alone leaves gaps of about 4h along the generator on random samplings.
  std::vector<float> facing(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i)
      facing[i] = normals[i].dot(camera.ray_direction(positions[i]));
  });
  const std::size_t m = std::min(o.interior_neighbours, neighbourhoods.k);
  // reach[i] = (largest n·v, largest −n·v) over i and its m nearest: how firmly each side is reached near i.
  std::vector<std::pair<float, float>> reach(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      float away = facing[i], toward = -facing[i];
      for (const std::uint32_t j : neighbourhoods.of(i).first(m)) {
        away = std::max(away, facing[j]);
        toward = std::max(toward, -facing[j]);
      }
      reach[i] = {away, toward};
    }
  });
  const float persistent = o.persistence_factor * normal_noise;
  // Side of f firmly reached near point i (the side f's sign says).
  const auto firm = [&](std::size_t i, float f) { return (f > 0 ? reach[i].first : reach[i].second) >= persistent; };
  // 180° is off: two opposite unit normals in float can give a dot a hair under cos 180° = -1.
  const float min_cos = o.interior_max_normal_angle_deg >= 180.f
                            ? -std::numeric_limits<float>::infinity()
                            : std::cos(o.interior_max_normal_angle_deg * kDegToRad);
  std::vector<Vec3f> sample(n);
  std::vector<char> has_sample(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const float fi = facing[i];
      if (fi == 0 || !std::isfinite(fi) || cp.spacing_px[i] <= 0 || !firm(i, fi)) continue;
      Vec3f sum = Vec3f::Zero();
      int count = 0;
      const auto nb = neighbourhoods.of(i);
      for (std::size_t a = 0; a < m; ++a) {
        const std::uint32_t j = nb[a];
        const float fj = facing[j];
        if (!(fi * fj < 0) || !firm(j, fj) || normals[i].dot(normals[j]) < min_cos) continue;
        const float t = fi / (fi - fj);
        sum += positions[i] + t * (positions[j] - positions[i]);
        ++count;
      }
      if (count > 0) {
        sample[i] = sum / static_cast<float>(count);
        has_sample[i] = 1;
      }
    }
  });
  for (std::size_t i = 0; i < n; ++i)
    if (has_sample[i]) {
      cp.rim.push_back(sample[i]);
      cp.rim_point.push_back(static_cast<std::uint32_t>(i));
    }
  // Read only where short contours are held to denoised_min_length_factor.
  if (denoised)
    cp.rim_bends = detail::rim_bends(positions, normals, neighbourhoods, facing, cp.rim_point, m, o.bend_min_f);
}

}  // namespace

ContourPoints find_contour_points(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                  const neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                                  const Camera& camera, const ContourOptions& o, float normal_noise,
                                  const std::vector<std::uint8_t>& border, bool denoised) {
  if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("contours: the mean spacing h must be positive");
  const std::size_t n = positions.size();
  if (!border.empty() && (border.size() != n || neighbourhoods.size() != n))
    throw Error("contours: the border has " + std::to_string(border.size()) + " entries for " + std::to_string(n) +
                " points (it needs the cloud's neighbourhoods too)");
  if (o.interior && n > 0) {
    if (normals.size() != n) throw Error("contours: interior contours need one normal per point (run analyse_surface)");
    if (neighbourhoods.size() != n || neighbourhoods.k == 0)
      throw Error("contours: interior contours need the cloud's neighbourhoods (run analyse_surface)");
  }
  ContourPoints cp;
  std::vector<float> unit = spacing_units(neighbourhoods, spacing, n, o.adaptive_spacing);
  cp.projected.resize(n);
  cp.spacing_px.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      cp.projected[i] = camera.project(positions[i]);
      const float depth = cp.projected[i].z();
      const bool in_front = camera.projection == Projection::Orthographic || depth > 0;
      cp.spacing_px[i] = in_front && cp.projected[i].allFinite() ? unit[i] / camera.units_per_pixel(depth) : 0.f;
    }
  });
  unit = std::vector<float>();  // freed before the image-plane grid, the peak of a draw

  detail::OutlinePoints outline = detail::find_outline_points(cp.projected, cp.spacing_px, neighbourhoods, border, o);
  cp.boundary = std::move(outline.boundary);
  cp.outward = std::move(outline.outward);
  if (o.interior && n > 0) {
    add_rim_samples(positions, normals, neighbourhoods, camera, o, normal_noise, denoised, cp);
    cp.depth_edges_begin = cp.rim.size();
    detail::add_depth_edge_samples(positions, normals, neighbourhoods, border, spacing, camera, o, cp);
  }
  return cp;
}

ContourLines connect_contours(const ContourPoints& points, const std::vector<Vec3f>& positions, float spacing,
                              const ContourOptions& options, bool denoised) {
  if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("contours: the mean spacing h must be positive");
  ContourLines lines;
  pcsketch::detail::ProgressSteps steps(options.progress, "contour connection",
                                        points.boundary.size() + (options.interior ? points.rim.size() : 0));
  lines.outline = trace_outline(points, positions, options, steps);
  detail::bridge_outline(points, positions, lines.outline, options);
  if (options.interior)
    lines.interior = detail::trace_interior(points, lines.outline, spacing, options, denoised, steps);
  steps.finish();
  return lines;
}

}  // namespace pcsketch::view
