#pragma once
// The walk that chains contour points into lines (the outline's in the image plane, interior rims in 3D): each step
// takes a point ahead chosen by the caller and marks those it passes as used.

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/view/contours.h"
#include "point_grid.h"

namespace pcsketch::view::detail {

/// Length of the polyline through `pts`, with the closing segment when `closed`.
inline float polyline_length(std::span<const Vec3f> pts, bool closed) {
  float length = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) length += (pts[i] - pts[i - 1]).norm();
  if (closed && pts.size() > 2) length += (pts.front() - pts.back()).norm();
  return length;
}

/// State shared by the walks over one set of contour points: positions (2D image or 3D), per-point search scale,
/// and the points already used (taken or absorbed).
template <int D>
struct Walker {
  using Vec = Eigen::Matrix<float, D, 1>;
  std::span<const Vec> pts;
  const detail::PointGrid<D>& grid;
  std::span<const float> scale;  ///< per point: the unit the radius factors multiply (h_px, or h in 3D)
  const ContourOptions& options;
  std::vector<char> used;

  /// Marks unused points beside or behind the step p → q (within `absorb` of the segment line, projection ≤ |pq|).
  void absorb(std::uint32_t from, std::uint32_t to, float absorb_radius) {
    const Vec p = pts[from];
    const Vec step = pts[to] - p;
    const float len = step.norm();
    if (len <= 0) return;
    const Vec dir = step / len;
    grid.for_each_within(p, len + absorb_radius, [&](std::uint32_t j, float) {
      if (used[j]) return;
      const Vec c = pts[j] - p;
      const float t = c.dot(dir);
      if (t > len || t < -absorb_radius) return;
      if ((c - t * dir).norm() < absorb_radius) used[j] = 1;
    });
  }

  /// Unit heading over the last `heading_steps` steps of the chain (n_p = p_front − p, smoothed).
  Vec heading(const std::vector<std::uint32_t>& chain) const {
    const std::size_t back = std::min(chain.size() - 1, std::max<std::size_t>(options.heading_steps, 1));
    Vec d = pts[chain.back()] - pts[chain[chain.size() - 1 - back]];
    const float len = d.norm();
    return len > 0 ? Vec(d / len) : d;
  }

  /// Grows `chain` (holding the seed) by repeatedly taking the point `choose(cur, heading)` returns; stops when it
  /// returns none or closes on the seed (only when `may_close`). Returns whether the chain closed.
  template <class Choose>
  bool grow(std::vector<std::uint32_t>& chain, Vec heading_now, bool may_close, Choose&& choose) {
    const std::uint32_t seed = chain.front();
    float walked = 0;
    for (;;) {
      const std::uint32_t cur = chain.back();
      const float radius = options.trace_radius_factor * scale[cur];
      const bool seed_eligible = may_close && chain.size() >= 4 && walked > 2 * radius;
      const std::int64_t next = choose(cur, heading_now, radius, seed_eligible ? seed : cur);
      if (next < 0) return false;
      const auto q = static_cast<std::uint32_t>(next);
      if (q == seed) return true;
      absorb(cur, q, options.absorb_factor * scale[cur]);
      walked += (pts[q] - pts[cur]).norm();
      used[q] = 1;
      chain.push_back(q);
      heading_now = heading(chain);
    }
  }

  /// Grows from `seed` forward (the chain may close on the seed), then, if it did not close, backward from the seed.
  /// Returns the points in order along the line and whether it closed.
  template <class ChooseForward, class ChooseBackward>
  std::pair<std::vector<std::uint32_t>, bool> grow_both_ways(std::uint32_t seed, Vec forward_heading,
                                                             ChooseForward&& forward_choose, Vec backward_heading,
                                                             ChooseBackward&& backward_choose) {
    std::vector<std::uint32_t> forward{seed};
    if (grow(forward, forward_heading, true, forward_choose)) return {std::move(forward), true};
    std::vector<std::uint32_t> chain{seed};
    grow(chain, backward_heading, false, backward_choose);
    std::reverse(chain.begin(), chain.end());
    chain.insert(chain.end(), forward.begin() + 1, forward.end());
    return {std::move(chain), false};
  }
};

}  // namespace pcsketch::view::detail
