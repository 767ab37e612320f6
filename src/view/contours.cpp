#include "pcsketch/view/contours.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>
#include <span>

#include "pcsketch/core/error.h"
#include "core/angular_gap.h"
#include "core/parallel_chunks.h"
#include "core/progress.h"
#include "contour_walk.h"
#include "image_cells.h"
#include "point_grid.h"

namespace pcsketch::view {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kDegToRad = kPi / 180.f;
/// Image cell, in mean point spacings, within which one point stands for all in the outline test.
constexpr float kImageCellFactor = 0.25f;

using pcsketch::detail::gap_exceeds;
using pcsketch::detail::largest_gap;
using pcsketch::detail::octant_bit;
using detail::polyline_length;
using detail::Walker;

/// The unit vector pointing to the empty side of heading d: side = +1 on the right of d in (u, v), −1 on the left.
Vec2f side_of(const Vec2f& d, float side) { return side * Vec2f(d.y(), -d.x()); }

/// The heading a walk starts with so that the empty direction `outward` lies on its `side`.
Vec2f heading_for(const Vec2f& outward, float side) { return side * Vec2f(-outward.y(), outward.x()); }

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

  // Returns the next point from `cur` along `d` with the empty side on `side`, or -1. `closing` is the seed when
  // it may close the line (else cur itself, which is never a candidate).
  auto chooser = [&](float side) {
    return [&, side](std::uint32_t cur, const Vec2f& d, float radius, std::uint32_t closing) -> std::int64_t {
      const Vec2f p = pts[cur];
      const Vec2f s = side_of(d, side);
      const float z_max = o.z_max_factor * scale[cur];
      std::int64_t best = -1;
      float best_score = 0, best_dist = 0;
      bool closes = false;
      grid.for_each_within(p, radius, [&](std::uint32_t j, float d2) {
        if (j == cur || (walker.used[j] && j != closing)) return;
        const Vec2f c = pts[j] - p;
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
    };
  };

  // Seeds from the left, as the paper does: the leftmost point is on the outer outline.
  std::vector<std::uint32_t> seeds(nb);
  std::iota(seeds.begin(), seeds.end(), 0u);
  std::sort(seeds.begin(), seeds.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (pts[a].x() != pts[b].x()) return pts[a].x() < pts[b].x();
    if (pts[a].y() != pts[b].y()) return pts[a].y() < pts[b].y();
    return a < b;
  });

  std::vector<Polyline> lines;
  for (std::size_t s = 0; s < nb; ++s) {
    steps.at(s);
    const std::uint32_t seed = seeds[s];
    if (walker.used[seed]) continue;
    walker.used[seed] = 1;
    const auto [chain, closed] = walker.grow_both_ways(seed, heading_for(cp.outward[seed], +1.f), chooser(+1.f),
                                                       heading_for(cp.outward[seed], -1.f), chooser(-1.f));
    Polyline line;
    line.kind = LineKind::Contour;
    line.closed = closed;
    std::vector<Vec3f> image(chain.size());
    float scale_sum = 0;
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const std::uint32_t point = cp.boundary[chain[i]];
      line.points.push_back(positions[point]);
      line.point_index.push_back(point);
      image[i] = Vec3f(pts[chain[i]].x(), pts[chain[i]].y(), 0.f);
      scale_sum += scale[chain[i]];
    }
    const float min_length = o.min_length_factor * scale_sum / static_cast<float>(chain.size());
    if (chain.size() >= 3 && polyline_length(image, closed) >= min_length) lines.push_back(std::move(line));
  }
  return lines;
}

/// Which rim samples the outline already draws: those within `dedupe` of its vertices or of points along its
/// segments every h/2. The outline's samples are visited one at a time against a grid of the rim, not stored: an
/// outline seen edge-on (a face parallel to the view) has 3D segments across the whole depth, and storing their
/// samples took memory growing as n^1.5 (174 MB of the 552 MB peak of a 200k-point fandisk).
std::vector<char> covered_by_outline(const std::vector<Vec3f>& rim, const std::vector<Polyline>& outline, float h,
                                     float dedupe) {
  const detail::PointGrid<3> rim_grid(rim, dedupe);
  std::vector<char> covered(rim.size(), 0);
  const auto cover = [&](const Vec3f& sample) {
    rim_grid.for_each_within(sample, dedupe, [&](std::uint32_t r, float) { covered[r] = 1; });
  };
  for (const Polyline& line : outline) {
    const std::size_t n = line.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (i + 1 == n && !line.closed) {
        cover(line.points[i]);
        break;
      }
      const Vec3f a = line.points[i], b = line.points[(i + 1) % n];
      const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / (0.5f * h))));
      for (int s = 0; s < steps; ++s) cover(a + (b - a) * (static_cast<float>(s) / static_cast<float>(steps)));
    }
  }
  return covered;
}

/// Chains the interior rim samples in 3D with the paper's rule (nearest ahead within z_max of the direction line),
/// after dropping those the outline already covers.
std::vector<Polyline> trace_interior(const ContourPoints& cp, const std::vector<Polyline>& outline, float h,
                                     const ContourOptions& o, float min_length_factor,
                                     pcsketch::detail::ProgressSteps& steps) {
  const float dedupe = o.interior_dedupe_factor * h;
  const std::vector<char> covered = covered_by_outline(cp.rim, outline, h, dedupe);
  std::vector<Vec3f> rim;
  std::vector<std::uint32_t> rim_point;
  for (std::size_t r = 0; r < cp.rim.size(); ++r) {
    if (covered[r]) continue;
    rim.push_back(cp.rim[r]);
    rim_point.push_back(cp.rim_point[r]);
  }
  if (rim.empty()) return {};

  const std::vector<float> scale(rim.size(), h);
  const float radius = o.interior_trace_radius_factor * h;
  const detail::PointGrid<3> grid(rim, radius);
  ContourOptions walk_options = o;
  walk_options.trace_radius_factor = o.interior_trace_radius_factor;
  Walker<3> walker{rim, grid, scale, walk_options, std::vector<char>(rim.size(), 0)};
  const float z_max = o.interior_z_max_factor * h;
  const float cos_turn = std::cos(o.max_turn_deg * kDegToRad);

  auto choose = [&](std::uint32_t cur, const Vec3f& d, float r, std::uint32_t closing) -> std::int64_t {
    const Vec3f p = rim[cur];
    std::int64_t best = -1;
    float best_d2 = 0;
    grid.for_each_within(p, r, [&](std::uint32_t j, float d2) {
      if (j == cur || (walker.used[j] && j != closing)) return;
      const Vec3f c = rim[j] - p;
      const float along = c.dot(d);
      if (along <= 0 || (c - along * d).norm() >= z_max || along < cos_turn * std::sqrt(d2)) return;
      if (best < 0 || d2 < best_d2 || (d2 == best_d2 && j < best)) {
        best = j;
        best_d2 = d2;
      }
    });
    return best;
  };

  std::vector<Polyline> lines;
  for (std::uint32_t seed = 0; seed < rim.size(); ++seed) {
    steps.at(cp.boundary.size() + seed);  // after the outline's seeds
    if (walker.used[seed]) continue;
    walker.used[seed] = 1;
    // Paper: the first direction points to p_front, the nearest unused point.
    std::int64_t front = -1;
    float front_d2 = 0;
    grid.for_each_within(rim[seed], radius, [&](std::uint32_t j, float d2) {
      if (j == seed || walker.used[j] || d2 <= 0) return;
      if (front < 0 || d2 < front_d2 || (d2 == front_d2 && j < front)) {
        front = j;
        front_d2 = d2;
      }
    });
    if (front < 0) continue;
    const Vec3f d0 = (rim[static_cast<std::size_t>(front)] - rim[seed]).normalized();
    const auto [chain, closed] = walker.grow_both_ways(seed, d0, choose, Vec3f(-d0), choose);
    Polyline line;
    line.kind = LineKind::Contour;
    line.closed = closed;
    for (const std::uint32_t c : chain) {
      line.points.push_back(rim[c]);
      line.point_index.push_back(rim_point[c]);
    }
    if (chain.size() >= 3 && polyline_length(line.points, closed) >= min_length_factor * h)
      lines.push_back(std::move(line));
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
  std::vector<float> sorted = far;
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  if (!(*mid > 0)) return std::vector<float>(n, h);
  // Averaged over the neighbours: one point's k-th distance scatters by about 30% on a random sampling.
  const float to_h = h / *mid;
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

/// The border points and their nearest `m` neighbours (empty without a border): the band of outline candidates a
/// border seen edge-on or through a hole makes is about r/2 wide, a border one or two points.
std::vector<std::uint8_t> border_band(const std::vector<std::uint8_t>& border,
                                      const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t m) {
  if (border.empty()) return {};
  std::vector<std::uint8_t> band = border;
  m = std::min(m, neighbourhoods.k);
  for (std::size_t i = 0; i < border.size(); ++i)
    if (border[i])
      for (const std::uint32_t j : neighbourhoods.of(i).first(m)) band[j] = 1;
  return band;
}

}  // namespace

ContourPoints find_contour_points(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                  const neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                                  const Camera& camera, const ContourOptions& o, float normal_noise,
                                  const std::vector<std::uint8_t>& border) {
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

  // Points behind a perspective eye are left out of the image-plane analysis.
  std::vector<std::uint32_t> valid;
  valid.reserve(n);
  double mean_px = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (cp.spacing_px[i] > 0) {
      valid.push_back(static_cast<std::uint32_t>(i));
      mean_px += cp.spacing_px[i];
    }
  if (!valid.empty()) {
    mean_px /= static_cast<double>(valid.size());
    // Points a quarter spacing apart in the image tell the outline test nothing new: one of each such cell is asked.
    // The spacing is a low percentile of the points' own, so that the dense parts of an uneven cloud keep theirs.
    valid = detail::first_in_image_cells(cp.projected, std::move(valid),
                                         kImageCellFactor * detail::low_spacing(cp.spacing_px, valid));
    std::vector<Vec2f> uv(valid.size());
    for (std::size_t v = 0; v < valid.size(); ++v) uv[v] = cp.projected[valid[v]].head<2>();
    const detail::PointGrid<2> grid(uv, o.radius_factor * static_cast<float>(mean_px));
    std::vector<char> is_boundary(valid.size(), 0);
    std::vector<Vec2f> outward(valid.size(), Vec2f::Zero());
    const float threshold = o.gap_threshold_deg * kDegToRad;
    const bool octant_shortcut = o.gap_threshold_deg >= 90.f;
    // Pre-filter: a point whose own 3D neighbours, projected, leave no gap over the threshold (and no empty
    // quadrant) is inside the projection: nothing projects beyond the outline, so an outline point's neighbours
    // leave a gap of about 180°. True of most points; it costs no 2D query. All eight 45° sectors filled settles
    // it without angles; irregular or foreshortened neighbourhoods (two thirds of the bunny's vertices) need the gap.
    const bool use_3d_neighbours = octant_shortcut && neighbourhoods.size() == n && neighbourhoods.k > 0;
    auto surrounded = [&](std::uint32_t i, std::vector<Vec2f>& dirs) {
      const Vec2f p = cp.projected[i].head<2>();
      const float min_d2 = 1e-8f * cp.spacing_px[i] * cp.spacing_px[i];
      unsigned octants = 0;
      dirs.clear();
      for (const std::uint32_t j : neighbourhoods.of(i)) {
        const Vec2f c = cp.projected[j].head<2>() - p;
        if (cp.spacing_px[j] > 0 && c.squaredNorm() > min_d2) {
          octants |= octant_bit(c);
          dirs.push_back(c);
        }
      }
      if (octants == 0xFFu) return true;
      if (((octants | (octants >> 4)) & 0xFu) != 0xFu) return false;
      return !gap_exceeds(dirs, threshold);
    };
    // The pre-filter runs in index order, where the 3D neighbourhoods are close in memory; the 2D queries run in
    // the grid's cell order so that neighbouring queries scan the same cells (cache).
    std::vector<char> inside(valid.size(), 0);
    if (use_3d_neighbours)
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, valid.size(), 256), [&](const auto& range) {
        std::vector<Vec2f> dirs;
        for (std::size_t v = range.begin(); v != range.end(); ++v) inside[v] = surrounded(valid[v], dirs);
      });
    const std::vector<std::uint32_t>& grid_order = grid.order();
    pcsketch::detail::parallel_chunks(valid.size(), o.progress, "contour points", [&](std::size_t begin, std::size_t end) {
      std::vector<std::pair<float, std::uint32_t>> near;
      std::vector<Vec2f> dirs;
      std::vector<float> angles;
      for (std::size_t g = begin; g != end; ++g) {
        const std::size_t v = grid_order[g];
        if (inside[v]) continue;
        const float r = o.radius_factor * cp.spacing_px[valid[v]];
        // Points within r filling all eight 45° sectors: no gap reaches 90° (interior). The scan for them starts
        // at v's own cell, which most often settles it; the points are then gathered in the grid's order.
        unsigned filled = 0;
        if (octant_shortcut && !grid.for_each_within_until_centre_first(uv[v], r, [&](std::uint32_t j, float d2) {
              if (d2 > 1e-8f * r * r) filled |= octant_bit(uv[j] - uv[v]);  // self and duplicates: no direction
              return filled != 0xFFu;
            }))
          continue;
        near.clear();
        grid.for_each_within(uv[v], r, [&](std::uint32_t j, float d2) {
          if (d2 > 1e-8f * r * r) near.emplace_back(d2, j);
        });
        if (near.size() > o.k) {
          std::nth_element(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(o.k), near.end());
          near.resize(o.k);
        }
        dirs.clear();
        unsigned octants = 0;
        for (const auto& [d2, j] : near) {
          const Vec2f c = uv[j] - uv[v];
          dirs.push_back(c);
          octants |= octant_bit(c);
        }
        // Quadrant q holds octants q and q + 4.
        const bool empty_quadrant = ((octants | (octants >> 4)) & 0xFu) != 0xFu;
        if (!((o.quadrant_test && empty_quadrant) || gap_exceeds(dirs, threshold))) continue;
        const Vec2f bisector = largest_gap(angles, dirs).second;
        // Confirmation: outside a true outline the empty region goes on, while a sampling hole inside the outline
        // (random sampling leaves some of about r) is closed beyond it.
        bool confirmed = true;
        if (o.confirm_factor > 1) {
          const float cos_cone = std::cos(o.confirm_half_angle_deg * kDegToRad);
          grid.for_each_within(uv[v], o.confirm_factor * r, [&](std::uint32_t j, float d2) {
            if (!confirmed || d2 <= r * r) return;
            const Vec2f c = uv[j] - uv[v];
            if (c.dot(bisector) > cos_cone * std::sqrt(d2)) confirmed = false;
          });
        }
        if (confirmed) {
          is_boundary[v] = 1;
          outward[v] = bisector;
        }
      }
    });
    const std::vector<std::uint8_t> near_border = border_band(border, neighbourhoods, o.interior_neighbours);
    for (std::size_t v = 0; v < valid.size(); ++v)
      if (is_boundary[v] && (near_border.empty() || !near_border[valid[v]])) {
        cp.boundary.push_back(valid[v]);
        cp.outward.push_back(outward[v]);
      }
  }

  if (o.interior && n > 0) {
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
          if (!(fi * fj < 0) || !firm(j, fj)) continue;
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
  if (options.interior)
    lines.interior = trace_interior(points, lines.outline, spacing, options,
                                    denoised ? options.denoised_min_length_factor : options.min_length_factor, steps);
  steps.finish();
  return lines;
}

}  // namespace pcsketch::view
