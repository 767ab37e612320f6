#include "depth_edges.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/angles.h"
#include "core/angular_gap.h"
#include "pcsketch/features/boundary_lines.h"
#include "point_grid.h"

namespace pcsketch::view::detail {

namespace {

using pcsketch::detail::kDegToRad;

/// A depth-edge candidate of the view and the bisector of the gap its projected neighbours leave in the image.
struct Candidate {
  std::uint32_t point;
  Vec2f bisector;
};

/// A surface that faces the viewer ends at a hole or a sheet's edge, not at an occluding contour (|n·v| = 0 there).
constexpr float kMaxFacing = 0.5f;
/// Bound on the cells of points_near's marks.
constexpr std::size_t kMaxCells = std::size_t{1} << 24;

/// The bisector of the gap point i's projected neighbours leave in the image, when it exceeds `threshold`.
std::optional<Vec2f> projected_gap(const ContourPoints& cp, const neighbourhood::Neighbourhoods& neighbourhoods,
                                   std::size_t i, float threshold, std::vector<Vec2f>& dirs,
                                   std::vector<float>& angles) {
  const Vec2f p = cp.projected[i].head<2>();
  const float min_d2 = 1e-8f * cp.spacing_px[i] * cp.spacing_px[i];
  dirs.clear();
  for (const std::uint32_t j : neighbourhoods.of(i)) {
    const Vec2f c = cp.projected[j].head<2>() - p;
    if (cp.spacing_px[j] > 0 && c.squaredNorm() > min_d2) dirs.push_back(c);
  }
  if (dirs.size() < 3 || !pcsketch::detail::gap_exceeds(dirs, threshold)) return std::nullopt;
  return pcsketch::detail::largest_gap(angles, dirs).second;
}

/// The edge points of `border` that do not face the viewer and leave a gap in the image. At a contour the tangent
/// plane holds the ray, so the surface's own gap points along the ray: only the image gives the direction across.
std::vector<Candidate> gap_candidates(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                      const neighbourhood::Neighbourhoods& neighbourhoods,
                                      const std::vector<std::uint8_t>& border, const Camera& camera,
                                      const ContourOptions& o, const ContourPoints& cp) {
  std::vector<Candidate> candidates;
  std::vector<Vec2f> dirs;
  std::vector<float> angles;
  const float threshold = o.gap_threshold_deg * kDegToRad;
  for (std::size_t i = 0; i < border.size(); ++i) {
    if (border[i] == 0 || cp.spacing_px[i] <= 0) continue;
    if (std::abs(normals[i].dot(camera.ray_direction(positions[i]))) > kMaxFacing) continue;
    if (const auto bisector = projected_gap(cp, neighbourhoods, i, threshold, dirs, angles))
      candidates.push_back({static_cast<std::uint32_t>(i), *bisector});
  }
  return candidates;
}

/// The points in the image within reach of some candidate's test: only they go into its grid (a closed cloud has a few
/// hundred candidates, and a grid over a million points cost more than all the tests). Cells as wide as the largest
/// reach, marked around each candidate; all the points when those cells would be too many (points far off the image).
std::vector<std::uint32_t> points_near(const ContourPoints& cp, const std::vector<Candidate>& candidates,
                                       float radius_factor) {
  float cell = 0;
  Eigen::AlignedBox2f box;
  for (const Candidate& c : candidates) {
    cell = std::max(cell, radius_factor * cp.spacing_px[c.point]);
    box.extend(cp.projected[c.point].head<2>());
  }
  box.min().array() -= cell;
  box.max().array() += cell;
  const Eigen::Array2f extent = (box.sizes() / cell).array().floor() + 1;
  const bool all = !(cell > 0 && extent.prod() <= static_cast<float>(kMaxCells));
  const int nx = all ? 0 : static_cast<int>(extent.x()), ny = all ? 0 : static_cast<int>(extent.y());
  // Cell coordinates, clamped: rounding may put a point on the box's edge one cell out.
  const auto cell_of = [&](const Vec2f& q) {
    const Eigen::Array2f c = ((q - box.min()) / cell).array().floor();
    return Eigen::Array2i(std::clamp(static_cast<int>(c.x()), 0, nx - 1),
                          std::clamp(static_cast<int>(c.y()), 0, ny - 1));
  };
  std::vector<char> marked(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
  if (!all)
    for (const Candidate& c : candidates) {
      const Eigen::Array2i centre = cell_of(cp.projected[c.point].head<2>());
      for (int y = std::max(centre.y() - 1, 0); y <= std::min(centre.y() + 1, ny - 1); ++y)
        for (int x = std::max(centre.x() - 1, 0); x <= std::min(centre.x() + 1, nx - 1); ++x)
          marked[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)] = 1;
    }
  std::vector<std::uint32_t> near;
  for (std::size_t i = 0; i < cp.projected.size(); ++i) {
    if (cp.spacing_px[i] <= 0) continue;
    const Vec2f q = cp.projected[i].head<2>();
    bool in = all;
    if (!in && box.contains(q)) {
      const Eigen::Array2i at = cell_of(q);
      in = marked[static_cast<std::size_t>(at.y()) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(at.x())];
    }
    if (in) near.push_back(static_cast<std::uint32_t>(i));
  }
  return near;
}

/// For each candidate, whether the points in the image beyond its gap exist and all lie far behind it.
std::vector<char> far_behind(const ContourPoints& cp, const std::vector<Candidate>& candidates, float h,
                             const ContourOptions& o) {
  const std::vector<std::uint32_t> near = points_near(cp, candidates, o.depth_edge_radius_factor);
  std::vector<Vec2f> uv(near.size());
  for (std::size_t v = 0; v < near.size(); ++v) uv[v] = cp.projected[near[v]].head<2>();
  float mean_r = 0;
  for (const Candidate& c : candidates) mean_r += o.depth_edge_radius_factor * cp.spacing_px[c.point];
  const PointGrid<2> grid(uv, mean_r / static_cast<float>(candidates.size()));
  const float cos_cone = std::cos(o.confirm_half_angle_deg * kDegToRad);
  std::vector<char> is_edge(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 64), [&](const auto& range) {
    for (std::size_t c = range.begin(); c != range.end(); ++c) {
      const std::uint32_t i = candidates[c].point;
      const Vec2f p = cp.projected[i].head<2>();
      const float r = o.depth_edge_radius_factor * cp.spacing_px[i];
      const float depth = cp.projected[i].z() + o.depth_edge_factor * h;
      std::size_t count = 0;
      const bool all_behind = grid.for_each_within_until(p, r, [&](std::uint32_t v, float d2) {
        const Vec2f d = uv[v] - p;
        if (d2 <= 1e-8f * r * r || d.dot(candidates[c].bisector) <= cos_cone * std::sqrt(d2)) return true;
        ++count;
        return cp.projected[near[v]].z() > depth;
      });
      is_edge[c] = all_behind && count > 0;
    }
  });
  return is_edge;
}

}  // namespace

void add_depth_edge_samples(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods,
                            const std::vector<std::uint8_t>& border, float h, const Camera& camera,
                            const ContourOptions& o, ContourPoints& cp) {
  if (!(o.depth_edge_factor > 0) || border.size() != positions.size() || neighbourhoods.size() != positions.size())
    return;
  const std::vector<Candidate> candidates = gap_candidates(positions, normals, neighbourhoods, border, camera, o, cp);
  if (candidates.empty()) return;
  const std::vector<char> is_edge = far_behind(cp, candidates, h, o);
  // The edge band is a few points deep along the ray: each sample keeps its point's place in the image, at the mean
  // depth of the edge points among its nearest. Chains through the points themselves zig-zag in depth and break.
  std::vector<char> edge_point(positions.size(), 0);
  for (std::size_t c = 0; c < candidates.size(); ++c) edge_point[candidates[c].point] = is_edge[c];
  const std::size_t m = std::min(o.interior_neighbours, neighbourhoods.k);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!is_edge[c]) continue;
    const std::uint32_t i = candidates[c].point;
    float depth = cp.projected[i].z();
    int count = 1;
    for (const std::uint32_t j : neighbourhoods.of(i).first(m))
      if (edge_point[j]) {
        depth += cp.projected[j].z();
        ++count;
      }
    const Vec3f ray = camera.ray_direction(positions[i]);
    const float along = ray.dot(camera.forward);
    const float shift = (depth / static_cast<float>(count) - cp.projected[i].z()) / std::max(along, 1e-3f);
    cp.rim.push_back(positions[i] + shift * ray);
    cp.rim_point.push_back(i);
  }
}

}  // namespace pcsketch::view::detail
