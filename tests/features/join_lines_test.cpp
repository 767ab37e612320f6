#include "pcsketch/features/join_lines.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pcsketch/core/error.h"

namespace pcsketch::features {
namespace {

// A straight polyline from a to b with `n` vertices, per-vertex curvature and point indices starting at `first`.
Polyline segment(const Vec3f& a, const Vec3f& b, int n, LineKind kind = LineKind::Ridge, std::uint32_t first = 0) {
  Polyline line;
  line.kind = kind;
  for (int i = 0; i < n; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(n - 1);
    line.points.push_back(a + t * (b - a));
    line.curvature.push_back(1.f);
    line.point_index.push_back(first + static_cast<std::uint32_t>(i));
  }
  return line;
}

// Options isolating joining: no smoothing, no length filter.
JoinOptions plain() { return {.min_length_factor = 0.f, .smoothing_iterations = 0}; }

constexpr float kH = 1.f;       // spacing h
constexpr float kRadius = 4.f;  // r = 4h; default reach 1.5 r = 6

TEST(JoinLines, CollinearBrokenSegmentsJoinInOrder) {
  // Gap of 3 (< 6) between (10,0,0) and (13,0,0); the second line is given reversed.
  std::vector<Polyline> lines = {segment({0, 0, 0}, {10, 0, 0}, 11, LineKind::Ridge, 0),
                                 segment({23, 0, 0}, {13, 0, 0}, 11, LineKind::Ridge, 100)};
  const JoinResult r = join_lines(lines, kRadius, kH, plain());
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_EQ(r.joins, 1u);
  const Polyline& l = r.lines[0];
  ASSERT_EQ(l.size(), 22u);
  EXPECT_EQ(l.curvature.size(), 22u);
  EXPECT_EQ(l.point_index.size(), 22u);
  EXPECT_NEAR(l.length(), 23.f, 1e-4f);
  // Monotonic in x: the reversed piece was turned around, its point indices follow their vertices.
  for (std::size_t i = 1; i < l.size(); ++i) EXPECT_GT(l.points[i].x(), l.points[i - 1].x());
  EXPECT_EQ(l.point_index[11], 110u);
  EXPECT_EQ(l.point_index[21], 100u);
}

TEST(JoinLines, GapBeyondReachStaysOpen) {
  std::vector<Polyline> lines = {segment({0, 0, 0}, {10, 0, 0}, 11), segment({16.5f, 0, 0}, {26, 0, 0}, 11)};
  EXPECT_EQ(join_lines(lines, kRadius, kH, plain()).lines.size(), 2u);
  // With a larger join factor the same gap closes.
  JoinOptions wide = plain();
  wide.join_distance_alpha = 2.f;
  EXPECT_EQ(join_lines(lines, kRadius, kH, wide).lines.size(), 1u);
}

TEST(JoinLines, PerpendicularLinesMeetingAtACornerDoNotJoin) {
  std::vector<Polyline> lines = {segment({0, 0, 0}, {10, 0, 0}, 11), segment({11, 1, 0}, {11, 11, 0}, 11)};
  const JoinResult r = join_lines(lines, kRadius, kH, plain());
  EXPECT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.joins, 0u);
}

TEST(JoinLines, AngleBetaIsRespected) {
  // The second line leaves the first one's end at 20° from straight on.
  const float a = 20.f * std::numbers::pi_v<float> / 180.f;
  const Vec3f start(12, 0, 0);
  const Vec3f dir(std::cos(a), std::sin(a), 0);
  std::vector<Polyline> lines = {segment({0, 0, 0}, {10, 0, 0}, 11), segment(start, start + 10.f * dir, 11)};
  JoinOptions loose = plain();
  loose.join_angle_beta_deg = 30.f;
  EXPECT_EQ(join_lines(lines, kRadius, kH, loose).lines.size(), 1u);
  JoinOptions strict = plain();
  strict.join_angle_beta_deg = 10.f;
  EXPECT_EQ(join_lines(lines, kRadius, kH, strict).lines.size(), 2u);
}

TEST(JoinLines, SideBySideParallelLinesDoNotJoin) {
  // Ends close together but both lines point the same way: tangents are not opposite.
  std::vector<Polyline> lines = {segment({0, 0, 0}, {10, 0, 0}, 11), segment({0, 2, 0}, {10, 2, 0}, 11)};
  EXPECT_EQ(join_lines(lines, kRadius, kH, plain()).lines.size(), 2u);
}

TEST(JoinLines, RidgeAndValleyNeverJoin) {
  std::vector<Polyline> lines = {segment({0, 0, 0}, {10, 0, 0}, 11, LineKind::Ridge),
                                 segment({12, 0, 0}, {22, 0, 0}, 11, LineKind::Valley)};
  EXPECT_EQ(join_lines(lines, kRadius, kH, plain()).lines.size(), 2u);
}

TEST(JoinLines, ChainOfFragmentsBecomesOneLine) {
  std::vector<Polyline> lines;
  for (int i = 0; i < 9; ++i) {
    const float x0 = 12.f * static_cast<float>(i);
    lines.push_back(segment({x0, 0, 0}, {x0 + 10.f, 0, 0}, 6));
  }
  const JoinResult r = join_lines(lines, kRadius, kH, plain());
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_EQ(r.joins, 8u);
  EXPECT_NEAR(r.lines[0].length(), 106.f, 1e-3f);
}

TEST(JoinLines, BrokenCircleCloses) {
  Polyline arc;
  const float radius = 60.f;
  for (int i = 0; i <= 118; ++i) {  // 0 … 354°: a gap of 6° ≈ 6.3 units
    const float t = static_cast<float>(i) * 3.f * std::numbers::pi_v<float> / 180.f;
    arc.points.emplace_back(radius * std::cos(t), radius * std::sin(t), 0.f);
  }
  arc.kind = LineKind::Valley;
  JoinOptions o = plain();
  o.join_distance_alpha = 2.f;
  const JoinResult r = join_lines({arc}, kRadius, kH, o);
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_TRUE(r.lines[0].closed);
}

TEST(JoinLines, ShortLinesDroppedAndSmoothingKeepsEndpoints) {
  Polyline zigzag;
  for (int i = 0; i <= 20; ++i) zigzag.points.emplace_back(static_cast<float>(i), (i % 2) ? 0.5f : -0.5f, 0.f);
  zigzag.points.back().y() = 0.3f;
  std::vector<Polyline> lines = {zigzag, segment({100, 0, 0}, {105, 0, 0}, 6)};  // the second is 5h < 8h long
  JoinOptions o;  // defaults: min length 8h, 2 smoothing passes
  const JoinResult r = join_lines(lines, kRadius, kH, o);
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_EQ(r.dropped, 1u);
  const Polyline& l = r.lines[0];
  EXPECT_EQ(l.points.front(), zigzag.points.front());
  EXPECT_EQ(l.points.back(), zigzag.points.back());
  for (std::size_t i = 2; i + 2 < l.size(); ++i) EXPECT_LT(std::abs(l.points[i].y()), 0.2f) << i;
}

TEST(JoinLines, RejectsBadOptions) {
  EXPECT_THROW(join_lines({}, 0.f, kH), Error);
  JoinOptions o;
  o.join_angle_beta_deg = 120.f;
  EXPECT_THROW(join_lines({}, kRadius, kH, o), Error);
}

}  // namespace
}  // namespace pcsketch::features
