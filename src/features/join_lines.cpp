#include "pcsketch/features/join_lines.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <tuple>

#include "core/angles.h"
#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/kd_tree.h"

namespace pcsketch::features {
namespace {

struct End {
  std::uint32_t line;
  std::uint8_t side;  // 0 = first vertex, 1 = last vertex
  Vec3f position;
  Vec3f tangent;  // unit, pointing out of the line
};

// Outward tangent at one end: from the vertex about `reach` back along the line (or the far end) to the end.
Vec3f end_tangent(const Polyline& line, std::uint8_t side, float reach) {
  const std::size_t n = line.size();
  const auto at = [&](std::size_t k) -> const Vec3f& { return side == 0 ? line.points[k] : line.points[n - 1 - k]; };
  float walked = 0.f;
  std::size_t k = 1;
  for (; k < n - 1; ++k) {
    walked += (at(k) - at(k - 1)).norm();
    if (walked >= reach) break;
  }
  const Vec3f t = at(0) - at(k);
  const float len = t.norm();
  return len > 0.f ? Vec3f(t / len) : Vec3f::Zero();
}

void smooth(Polyline& line, int iterations, float weight) {
  const std::size_t n = line.size();
  if (n < 3) return;
  std::vector<Vec3f> next(n);
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < n; ++i) {
      const bool end = !line.closed && (i == 0 || i == n - 1);
      if (end) {
        next[i] = line.points[i];
        continue;
      }
      const Vec3f& prev = line.points[(i + n - 1) % n];
      const Vec3f& succ = line.points[(i + 1) % n];
      next[i] = (1.f - weight) * line.points[i] + weight * 0.5f * (prev + succ);
    }
    line.points.swap(next);
  }
}

}  // namespace

JoinResult join_lines(std::vector<Polyline> lines, float radius, float spacing, const JoinOptions& options) {
  if (!(radius > 0.f) || !(spacing > 0.f)) throw Error("ridge/valley joining: radius r and spacing h must be positive");
  if (!(options.join_distance_alpha >= 0.f)) throw Error("ridge/valley joining: join distance alpha must be >= 0");
  if (!(options.join_angle_beta_deg >= 0.f && options.join_angle_beta_deg <= 90.f))
    throw Error("ridge/valley joining: join angle beta must be in [0, 90] degrees");
  if (options.smoothing_iterations < 0 || !(options.smoothing_weight >= 0.f && options.smoothing_weight <= 1.f))
    throw Error("ridge/valley joining: smoothing iterations must be >= 0 and weight in [0, 1]");

  const float reach = options.join_distance_alpha * radius;
  const float cos_beta = std::cos(options.join_angle_beta_deg * pcsketch::detail::kDegToRad);
  JoinResult result;
  std::vector<bool> alive(lines.size(), true);

  for (;;) {
    std::vector<End> ends;
    for (std::uint32_t l = 0; l < lines.size(); ++l) {
      if (!alive[l] || lines[l].closed || lines[l].size() < 2) continue;
      for (std::uint8_t side : {std::uint8_t{0}, std::uint8_t{1}}) {
        // Over 2r the lateral wobble of the vertices (up to about h) tilts the tangent by a few degrees only.
        const Vec3f tangent = end_tangent(lines[l], side, 2.f * radius);
        if (tangent.isZero()) continue;
        ends.push_back({l, side, side == 0 ? lines[l].points.front() : lines[l].points.back(), tangent});
      }
    }
    if (ends.empty()) break;
    std::vector<Vec3f> positions(ends.size());
    for (std::size_t e = 0; e < ends.size(); ++e) positions[e] = ends[e].position;
    const neighbourhood::KdTree tree(positions);

    // Every qualifying pair, closest first; ties in line order, so the outcome depends only on the input order.
    std::vector<std::tuple<float, std::uint32_t, std::uint32_t>> pairs;
    std::vector<std::uint32_t> hits;
    std::vector<float> distances;
    for (std::uint32_t a = 0; a < ends.size(); ++a) {
      tree.radius(ends[a].position, reach, hits, distances);
      for (std::size_t h = 0; h < hits.size(); ++h) {
        const std::uint32_t b = hits[h];
        if (b <= a) continue;
        const End& p = ends[a];
        const End& q = ends[b];
        if (lines[p.line].kind != lines[q.line].kind) continue;
        if (p.line == q.line && lines[p.line].length() < 2.f * reach) continue;  // a short line cannot close
        if (-p.tangent.dot(q.tangent) < cos_beta) continue;
        const Vec3f d = q.position - p.position;
        if (distances[h] > radius) {
          // A long gap: each tangent must aim at the other endpoint within β.
          if (p.tangent.dot(d) < cos_beta * distances[h] || -q.tangent.dot(d) < cos_beta * distances[h]) continue;
        } else if (p.tangent.dot(d) < 0.f || -q.tangent.dot(d) < 0.f) {
          // A short gap: the lateral offset of the two ends (up to about h) would swamp the angle of the connecting
          // segment, so it is enough that each end lies ahead of the other.
          continue;
        }
        pairs.emplace_back(distances[h], a, b);
      }
    }
    std::sort(pairs.begin(), pairs.end());

    // One join per line per pass: ends and tangents of a joined line are stale until the next pass.
    std::vector<bool> touched(lines.size(), false);
    std::size_t joined = 0;
    for (const auto& [distance, a, b] : pairs) {
      const End& p = ends[a];
      const End& q = ends[b];
      if (touched[p.line] || touched[q.line]) continue;
      touched[p.line] = touched[q.line] = true;
      ++joined;
      if (p.line == q.line) {
        lines[p.line].closed = true;
        continue;
      }
      // The merged line keeps the earlier slot: line order stays the order of first seeds.
      const std::uint32_t keep = std::min(p.line, q.line);
      const End& kept_end = p.line == keep ? p : q;
      const End& other_end = p.line == keep ? q : p;
      Polyline& target = lines[keep];
      Polyline& source = lines[other_end.line];
      if (kept_end.side == 0) target.reverse();
      if (other_end.side == 1) source.reverse();
      target.append(std::move(source));
      alive[other_end.line] = false;
    }
    result.joins += joined;
    if (joined == 0) break;
  }

  const float min_length = options.min_length ? *options.min_length : options.min_length_factor * spacing;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    if (!alive[l]) continue;
    if (lines[l].length() < min_length) {
      ++result.dropped;
      continue;
    }
    smooth(lines[l], options.smoothing_iterations, options.smoothing_weight);
    result.lines.push_back(std::move(lines[l]));
  }
  return result;
}

}  // namespace pcsketch::features
