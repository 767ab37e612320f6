#include "pcsketch/features/trace_lines.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "pcsketch/core/error.h"

namespace pcsketch::features {
namespace {

// A synthetic labelled cloud: bands of feature points (jittered, a few points wide) on a sparse background.
struct Synthetic {
  std::vector<Vec3f> points;
  std::vector<PointLabel> labels;
  std::vector<float> curvature;

  // A band along `path(t)`, t in [0, 1], of length `length` at about one point per unit, `width` wide (in the
  // direction `across`).
  template <typename Path>
  void band(Path path, float length, const Vec3f& across, float width, PointLabel label, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    const int n = static_cast<int>(length * width);
    for (int i = 0; i < n; ++i) {
      const float t = (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
      points.push_back(path(t) + width * u(rng) * across + 0.2f * Vec3f(u(rng), u(rng), u(rng)));
      labels.push_back(label);
      curvature.push_back(label == PointLabel::Ridge ? 1.f : -1.f);
    }
  }
};

// Distance from p to the segment [a, b].
float segment_distance(const Vec3f& p, const Vec3f& a, const Vec3f& b) {
  const Vec3f ab = b - a;
  const float t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.f, 1.f);
  return (p - (a + t * ab)).norm();
}

constexpr float kH = 1.f;

TEST(TraceLines, StraightBandGivesOneCentredLine) {
  std::mt19937 rng(42);
  Synthetic s;
  const Vec3f a(0, 0, 0), b(60, 0, 0);
  s.band([&](float t) -> Vec3f { return a + t * (b - a); }, 60.f, Vec3f::UnitY(), 3.f, PointLabel::Ridge, rng);
  const TraceResult r = trace_lines(s.points, s.labels, s.curvature, kH);
  EXPECT_FLOAT_EQ(r.radius, 6.f);  // default 6h
  ASSERT_EQ(r.lines.size(), 1u);
  const Polyline& l = r.lines[0];
  EXPECT_EQ(l.kind, LineKind::Ridge);
  ASSERT_EQ(l.curvature.size(), l.size());
  ASSERT_EQ(l.point_index.size(), l.size());
  // Centre line of the 3-wide band (one point per unit², so a cross-section holds ~3 points), not a zig-zag through
  // its points, which would reach |y| = 1.5.
  float mean_offset = 0.f;
  for (const Vec3f& p : l.points) {
    EXPECT_LT(std::abs(p.y()), 1.f) << p.transpose();
    mean_offset += std::abs(p.y()) / static_cast<float>(l.size());
  }
  EXPECT_LT(mean_offset, 0.4f);
  // Ordered: x strictly monotonic (either way), and the line spans the band.
  const float sign = l.points.back().x() > l.points.front().x() ? 1.f : -1.f;
  for (std::size_t i = 1; i < l.size(); ++i) EXPECT_GT(sign * (l.points[i].x() - l.points[i - 1].x()), 0.f);
  EXPECT_GT(l.length(), 55.f);
  for (std::size_t i = 0; i < l.size(); ++i) {
    EXPECT_FLOAT_EQ(l.curvature[i], 1.f);
    EXPECT_LT((s.points[l.point_index[i]] - l.points[i]).norm(), 2.f);
  }
}

TEST(TraceLines, CornerGivesTwoLinesThatDoNotCutAcross) {
  std::mt19937 rng(7);
  Synthetic s;
  const Vec3f corner(40, 0, 0);
  s.band([&](float t) -> Vec3f { return Vec3f(40.f * t, 0, 0); }, 40.f, Vec3f::UnitY(), 2.f, PointLabel::Ridge, rng);
  s.band([&](float t) -> Vec3f { return corner + Vec3f(0, 40.f * t, 0); }, 40.f, Vec3f::UnitX(), 2.f, PointLabel::Ridge, rng);
  const TraceResult r = trace_lines(s.points, s.labels, s.curvature, kH);
  ASSERT_EQ(r.lines.size(), 2u);
  for (const Polyline& l : r.lines)
    for (const Vec3f& p : l.points)
      EXPECT_LT(std::min(segment_distance(p, {0, 0, 0}, corner), segment_distance(p, corner, {40, 40, 0})), 1.5f);
}

TEST(TraceLines, RidgeAndValleyTracedSeparately) {
  std::mt19937 rng(3);
  Synthetic s;
  // A ridge band crossed by a valley band: each kind gives its own straight line through the crossing.
  s.band([](float t) -> Vec3f { return Vec3f(60.f * t - 30.f, 0, 0); }, 60.f, Vec3f::UnitY(), 2.f, PointLabel::Ridge, rng);
  s.band([](float t) -> Vec3f { return Vec3f(0, 60.f * t - 30.f, 0); }, 60.f, Vec3f::UnitX(), 2.f, PointLabel::Valley, rng);
  const TraceResult r = trace_lines(s.points, s.labels, s.curvature, kH);
  ASSERT_EQ(r.lines.size(), 2u);
  ASSERT_EQ(r.seeds.size(), 2u);
  EXPECT_LT(r.seeds[0], r.seeds[1]);
  for (const Polyline& l : r.lines) {
    const bool ridge = l.kind == LineKind::Ridge;
    EXPECT_GT(l.length(), 55.f);
    for (std::size_t i = 0; i < l.size(); ++i) {
      EXPECT_LT(std::abs(ridge ? l.points[i].y() : l.points[i].x()), 0.6f);
      EXPECT_EQ(s.labels[l.point_index[i]], ridge ? PointLabel::Ridge : PointLabel::Valley);
    }
  }
}

TEST(TraceLines, CircleBandGivesClosedLine) {
  std::mt19937 rng(11);
  Synthetic s;
  const float radius = 30.f;
  const float two_pi = 2.f * std::numbers::pi_v<float>;
  // Radial jitter only: `across` would have to turn with the path, so use a thin band.
  s.band([&](float t) -> Vec3f { return Vec3f(radius * std::cos(two_pi * t), radius * std::sin(two_pi * t), 0); },
         two_pi * radius, Vec3f::UnitZ(), 1.f, PointLabel::Ridge, rng);
  const TraceResult r = trace_lines(s.points, s.labels, s.curvature, kH);
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_TRUE(r.lines[0].closed);
  for (const Vec3f& p : r.lines[0].points) EXPECT_NEAR(p.head<2>().norm(), radius, 0.5f);
  EXPECT_NEAR(r.lines[0].length(), two_pi * radius, 0.05f * two_pi * radius);
}

TEST(TraceLines, ScatteredPointsGiveNoLongLines) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 100.f);
  Synthetic s;
  for (int i = 0; i < 200; ++i) {  // mean distance between points ≫ r
    s.points.emplace_back(u(rng), u(rng), 0.f);
    s.labels.push_back(PointLabel::Ridge);
    s.curvature.push_back(1.f);
  }
  // r = 2 while neighbouring points are about 3.5 apart: almost every point is isolated.
  const TraceResult r = trace_lines(s.points, s.labels, s.curvature, kH, {.radius = 2.f});
  for (const Polyline& l : r.lines) EXPECT_LT(l.length(), 4.f);
}

TEST(TraceLines, UnlabelledPointsAreIgnoredAndBadInputRejected) {
  std::vector<Vec3f> points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  std::vector<PointLabel> none(3, PointLabel::None);
  std::vector<float> k(3, 0.f);
  EXPECT_TRUE(trace_lines(points, none, k, kH).lines.empty());
  EXPECT_THROW(trace_lines(points, none, {0.f}, kH), Error);
  EXPECT_THROW(trace_lines(points, none, k, 0.f), Error);
}

}  // namespace
}  // namespace pcsketch::features
