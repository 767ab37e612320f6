#include "interior_contours.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "contour_walk.h"
#include "core/angles.h"
#include "point_grid.h"

namespace pcsketch::view::detail {

namespace {

using pcsketch::detail::kDegToRad;

/// Which rim samples the outline already draws: those within `dedupe` of its vertices or of points along its
/// segments every h/2. The outline's samples are visited one at a time against a grid of the rim, not stored: an
/// outline seen edge-on (a face parallel to the view) has 3D segments across the whole depth, and storing their
/// samples took memory growing as n^1.5 (174 MB of the 552 MB peak of a 200k-point fandisk).
std::vector<char> covered_by_outline(const std::vector<Vec3f>& rim, const std::vector<Polyline>& outline, float h,
                                     float dedupe) {
  const PointGrid<3> rim_grid(rim, dedupe);
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

}  // namespace

std::vector<Polyline> trace_interior(const ContourPoints& cp, const std::vector<Polyline>& outline, float h,
                                     const ContourOptions& o, bool denoised, pcsketch::detail::ProgressSteps& steps) {
  const float dedupe = o.interior_dedupe_factor * h;
  const std::vector<char> covered = covered_by_outline(cp.rim, outline, h, dedupe);
  std::vector<Vec3f> rim;
  std::vector<std::uint32_t> rim_point;
  std::vector<char> depth_edge, bends;
  for (std::size_t r = 0; r < cp.rim.size(); ++r) {
    if (covered[r]) continue;
    rim.push_back(cp.rim[r]);
    rim_point.push_back(cp.rim_point[r]);
    depth_edge.push_back(r >= cp.depth_edges_begin);
    bends.push_back(r < cp.rim_bends.size() && cp.rim_bends[r]);
  }
  if (rim.empty()) return {};
  const bool bends_known = denoised && !cp.rim_bends.empty();

  const std::vector<float> scale(rim.size(), h);
  const float radius = o.interior_trace_radius_factor * h;
  const PointGrid<3> grid(rim, radius);
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
    std::size_t edges = 0, bending = 0;
    for (const std::uint32_t c : chain) {
      line.points.push_back(rim[c]);
      line.point_index.push_back(rim_point[c]);
      edges += depth_edge[c] ? 1 : 0;
      bending += bends[c] ? 1 : 0;
    }
    // A chain of depth edges, or of samples across which n·v bends, is no squiggle of noisy normals: it keeps the
    // clean clouds' minimum length. On a denoised cloud one that hardly bends is noise at any length (the sides of a
    // sheet thinner than the noise interleave), when the bends were computed.
    const bool edge_chain = 2 * edges >= chain.size();
    const auto bend_share = static_cast<float>(bending) / static_cast<float>(chain.size());
    if (bends_known && !edge_chain && bend_share < o.denoised_min_bending) continue;
    const bool firm = !denoised || edge_chain || 2 * bending >= chain.size();
    const float min_length = firm ? o.min_length_factor : o.denoised_min_length_factor;
    if (chain.size() >= 3 && polyline_length(line.points, closed) >= min_length * h) lines.push_back(std::move(line));
  }
  return lines;
}

}  // namespace pcsketch::view::detail
