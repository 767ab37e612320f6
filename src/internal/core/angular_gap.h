#pragma once
// The largest angular gap between directions around a point: the boundary tests of the outline (image plane) and of
// an open scan's border (tangent plane) both ask it.

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::detail {

inline constexpr float kGapPi = 3.14159265358979f;

/// Largest angular gap between the directions `dirs` (unit not required): its size in radians and the unit
/// direction of its bisector. Fewer than two directions: a full (or one-sided) gap.
inline std::pair<float, Vec2f> largest_gap(std::vector<float>& angles, std::span<const Vec2f> dirs) {
  if (dirs.empty()) return {2 * kGapPi, Vec2f(-1.f, 0.f)};
  angles.resize(dirs.size());
  for (std::size_t i = 0; i < dirs.size(); ++i) angles[i] = std::atan2(dirs[i].y(), dirs[i].x());
  std::sort(angles.begin(), angles.end());
  float best = angles.front() + 2 * kGapPi - angles.back();  // the gap across ±π
  float start = angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) {
    const float g = angles[i] - angles[i - 1];
    if (g > best) {
      best = g;
      start = angles[i - 1];
    }
  }
  const float mid = start + 0.5f * best;
  return {best, Vec2f(std::cos(mid), std::sin(mid))};
}

/// Increases with the angle of d from +x over [0, 4) as atan2 does over [0, 2π), without the trigonometry.
inline float pseudo_angle(const Vec2f& d) {
  const float p = d.x() / (std::abs(d.x()) + std::abs(d.y()));
  return d.y() < 0 ? 3.f + p : 1.f - p;
}

/// largest_gap(dirs).first > threshold, without arctangents: the boundary test asks it of every point and most
/// answers are no. `dirs` (none zero) is reordered by angle.
inline bool gap_exceeds(std::vector<Vec2f>& dirs, float threshold) {
  if (dirs.size() < 2) return threshold < 2 * kGapPi;
  std::sort(dirs.begin(), dirs.end(), [](const Vec2f& a, const Vec2f& b) { return pseudo_angle(a) < pseudo_angle(b); });
  const float cos_t = std::cos(threshold);
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const Vec2f& a = dirs[i];
    const Vec2f& b = dirs[(i + 1) % dirs.size()];
    const float cross = a.x() * b.y() - a.y() * b.x();
    const float dot_bound = cos_t * a.norm() * b.norm();
    // The counter-clockwise angle from a to b is over 180° where cross < 0; its cosine falls over [0°, 180°] and
    // rises over [180°, 360°].
    if (threshold < kGapPi ? (cross < 0 || a.dot(b) < dot_bound) : (cross < 0 && a.dot(b) > dot_bound)) return true;
  }
  return false;
}

/// Bit of the 45° sector holding direction c: quadrant q (by signs) is bit q, or bit q + 4 past its diagonal.
inline unsigned octant_bit(const Vec2f& c) {
  return 1u << ((c.x() >= 0 ? 0 : 1) + (c.y() >= 0 ? 0 : 2) + (std::abs(c.x()) >= std::abs(c.y()) ? 0 : 4));
}

}  // namespace pcsketch::detail
