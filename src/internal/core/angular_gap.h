#pragma once
// The largest angular gap between directions around a point: the boundary tests of the outline (image plane) and of
// an open scan's border (tangent plane) both ask it.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "ordered_key.h"
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

/// Bound on |approx_angle(d) - the angle of d|, radians.
inline constexpr float kApproxAngleError = 0.005f;

/// The angle of d from +x in [0, 2π), within kApproxAngleError (atan t ≈ πt/4 + 0.273 t(1 − t) on each octant, off
/// by at most 0.0038): a tenth of the cost of atan2.
inline float approx_angle(const Vec2f& d) {
  const float ax = std::abs(d.x()), ay = std::abs(d.y());
  const float t = std::min(ax, ay) / std::max(ax, ay);
  float a = t * (0.25f * kGapPi + 0.273f * (1 - t));  // [0, π/4]
  // Reflections by arithmetic, not branches: the signs are random from one direction to the next.
  a += static_cast<float>(ay > ax) * (0.5f * kGapPi - 2 * a);  // first quadrant
  a += static_cast<float>(d.x() < 0) * (kGapPi - 2 * a);       // upper half
  a += static_cast<float>(d.y() < 0) * (2 * kGapPi - 2 * a);   // [0, 2π]
  return std::max(a, 0.f);
}

/// largest_gap(dirs).first > threshold, without arctangents: the boundary test asks it of every point and most
/// answers are no. `dirs` holds no zero direction. The directions are ordered by one key each, (pseudo-angle bits,
/// index) in one word, not by a comparator that recomputes two pseudo-angles per comparison (the test was 6% of a
/// 1M-point draw); ties in angle keep their index order. Most points never get that far (the sieve below).
inline bool gap_exceeds(std::span<const Vec2f> dirs, float threshold) {
  if (dirs.size() < 2) return threshold < 2 * kGapPi;
  // First a sieve without sorting: 64 bins of equal angle. A gap over the threshold holds a run of whole empty bins
  // as wide as the threshold less the angles' error on both sides, less one bin at each end. No such run: no gap.
  constexpr float kBin = 2 * kGapPi / 64, kPerBin = 1 / kBin;
  if (const int run = static_cast<int>(std::floor((threshold - 2 * kApproxAngleError) / kBin)) - 2; run >= 1) {
    std::uint64_t filled = 0;
    for (const Vec2f& d : dirs) {
      const float bin = approx_angle(d) * kPerBin;
      filled |= std::uint64_t{1} << (bin >= 0 ? std::min(63, static_cast<int>(bin)) : 0);  // NaN: bin 0
    }
    std::uint64_t empty_run = ~filled;
    for (int r = 1; r < run && empty_run != 0; ++r) empty_run &= std::rotr(~filled, r);
    if (empty_run == 0) return false;
  }
  thread_local std::vector<std::uint64_t> order;
  order.resize(dirs.size());
  for (std::size_t i = 0; i < dirs.size(); ++i)
    order[i] = ordered_key(pseudo_angle(dirs[i]), static_cast<std::uint32_t>(i));  // pseudo-angles are ≥ 0
  std::sort(order.begin(), order.end());
  const float cos_t = std::cos(threshold);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Vec2f& a = dirs[key_index(order[i])];
    const Vec2f& b = dirs[key_index(order[(i + 1) % order.size()])];
    const float cross = a.x() * b.y() - a.y() * b.x();
    const float dot_bound = cos_t * a.norm() * b.norm();
    // The counter-clockwise angle from a to b is over 180° where cross < 0; its cosine falls over [0°, 180°] and
    // rises over [180°, 360°].
    if (threshold < kGapPi ? (cross < 0 || a.dot(b) < dot_bound) : (cross < 0 && a.dot(b) > dot_bound)) return true;
  }
  return false;
}

/// Width of sector_bit's sixteen sectors, radians.
inline constexpr float kSector = 2 * kGapPi / 16;

/// Bit of the 22.5° sector holding direction c (not zero), numbered counter-clockwise from +x: bit s holds the
/// angles from s · 22.5° to (s + 1) · 22.5°, each edge going to one side or the other. The quarter of the quadrant
/// by comparisons with the diagonal and tan 22.5°, then reflected by the signs: no angle.
inline std::uint16_t sector_bit(const Vec2f& c) {
  constexpr float kTan = 0.41421356f;  // tan 22.5°
  const float ax = std::abs(c.x()), ay = std::abs(c.y());
  const unsigned q = unsigned{ay >= kTan * ax} + unsigned{ay >= ax} + unsigned{ax <= kTan * ay};  // 0 to 3 from +x
  // Reflections by the sign bits: x < 0 gives 7 − q = q ^ 7, then y < 0 gives 15 − s = s ^ 15. The compiler made
  // branches of `(c.x() < 0) * …`, and the signs are random from one direction to the next: the boundary candidates'
  // loop took twice the time. A zero of either sign lies on an edge, where either side will do.
  const unsigned x_negative = std::bit_cast<std::uint32_t>(c.x()) >> 31;
  const unsigned y_negative = std::bit_cast<std::uint32_t>(c.y()) >> 31;
  return static_cast<std::uint16_t>(1u << (q ^ (7 * x_negative) ^ (15 * y_negative)));
}

/// True when the sectors `filled` (the sector_bit of every direction) prove that no gap exceeds `threshold`, so
/// that gap_exceeds would say no. A gap wider than the threshold holds floor(threshold / 22.5°) − 1 whole sectors
/// in a row (the sectors it cuts at its ends may hold its end directions): where the empty sectors make no such
/// run there is no such gap. The margin, far over the rounding of the sector edges and of gap_exceeds' cross and
/// dot products (about 1e-6 rad), keeps the answer exact.
inline bool sectors_rule_out_gap(std::uint16_t filled, float threshold) {
  constexpr float kMargin = 1e-3f;
  const int run = static_cast<int>(std::floor((threshold - kMargin) / kSector)) - 1;
  if (run < 1) return false;
  const auto empty = static_cast<std::uint16_t>(~filled);
  std::uint16_t starts = empty;  // bit s: sectors s to s + r all empty
  for (int r = 1; r < run && starts != 0; ++r) starts &= std::rotr(empty, r);
  return starts == 0;
}

/// Bit of the 45° sector holding direction c: quadrant q (by signs) is bit q, or bit q + 4 past its diagonal.
inline unsigned octant_bit(const Vec2f& c) {
  return 1u << ((c.x() >= 0 ? 0 : 1) + (c.y() >= 0 ? 0 : 2) + (std::abs(c.x()) >= std::abs(c.y()) ? 0 : 4));
}

}  // namespace pcsketch::detail
