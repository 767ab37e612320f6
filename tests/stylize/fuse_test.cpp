// Fusion of doubled lines: known answers on straight strokes a few pixels apart.

#include "pcsketch/stylize/fuse.h"

#include <gtest/gtest.h>

#include "pcsketch/core/error.h"

namespace pcsketch::stylize {
namespace {

/// A stroke of `count` vertices evenly from a to b (image = xy of the 3D points), width 1.
Stroke straight(LineKind kind, const Vec2f& a, const Vec2f& b, int count) {
  Stroke s;
  s.kind = kind;
  for (int i = 0; i < count; ++i) {
    const Vec2f p = a + (b - a) * (static_cast<float>(i) / static_cast<float>(count - 1));
    s.points.emplace_back(p.x(), p.y(), 0.f);
    s.image_points.push_back(p);
    s.widths.push_back(1.f);
  }
  s.half_widths.assign(2 * s.segments(), 1.f);
  return s;
}

/// Appends the vertices of `b` after the last of `a` (their first point being a's last).
Stroke joined(Stroke a, const Stroke& b) {
  for (std::size_t i = 1; i < b.points.size(); ++i) {
    a.points.push_back(b.points[i]);
    a.image_points.push_back(b.image_points[i]);
    a.widths.push_back(1.f);
  }
  a.half_widths.assign(2 * a.segments(), 1.f);
  return a;
}

constexpr float kPen = 3.f;  // fusion distance 6 px at the default 2 pen widths

TEST(Fuse, ARidgeAlongTheOutlineIsDrawnOnceAsTheOutline) {
  std::vector<Stroke> in = {straight(LineKind::Contour, {0, 0}, {100, 0}, 51),
                            straight(LineKind::Ridge, {0, 3}, {100, 3}, 34)};
  const FusionResult r = fuse_strokes(in, {FusionRank::Outline, FusionRank::Feature}, kPen);
  ASSERT_EQ(r.strokes.size(), 2u);
  EXPECT_FALSE(r.strokes[0].fused_into.has_value());
  ASSERT_TRUE(r.strokes[1].fused_into.has_value());
  EXPECT_EQ(*r.strokes[1].fused_into, 0u);
  EXPECT_EQ(r.strokes[1].kind, LineKind::Ridge);  // kept, with its own kind and points
  EXPECT_EQ(r.strokes[1].points.size(), 34u);
  EXPECT_EQ(r.fused_stretches, 1u);
}

TEST(Fuse, TheOutlineWinsWhateverTheOrderAndLength) {
  // The ridge comes first and is longer: the outline is still the one drawn.
  std::vector<Stroke> in = {straight(LineKind::Ridge, {-20, 2}, {120, 2}, 71),
                            straight(LineKind::Contour, {0, 0}, {100, 0}, 51)};
  const FusionResult r = fuse_strokes(in, {FusionRank::Feature, FusionRank::Outline}, kPen);
  // The ridge is cut into its free end, the stretch along the outline, and its other free end.
  ASSERT_EQ(r.strokes.size(), 4u);
  std::size_t fused = 0;
  for (const Stroke& s : r.strokes)
    if (s.fused_into) {
      ++fused;
      EXPECT_EQ(s.kind, LineKind::Ridge);
      EXPECT_EQ(r.strokes[*s.fused_into].kind, LineKind::Contour);
      for (const Vec2f& p : s.image_points) EXPECT_GE(p.x(), -8.f);
    }
  EXPECT_EQ(fused, 1u);
}

TEST(Fuse, OnlyTheStretchAlongsideIsFusedAndThePiecesMeet) {
  // A ridge runs along the contour for 60 px, then turns away down to y = 60.
  const Stroke ridge =
      joined(straight(LineKind::Ridge, {0, 3}, {60, 3}, 31), straight(LineKind::Ridge, {60, 3}, {60, 60}, 30));
  std::vector<Stroke> in = {straight(LineKind::Contour, {0, 0}, {100, 0}, 51), ridge};
  const FusionResult r = fuse_strokes(in, {FusionRank::Outline, FusionRank::Feature}, kPen);
  ASSERT_EQ(r.strokes.size(), 3u);
  const Stroke& along = r.strokes[1];
  const Stroke& away = r.strokes[2];
  ASSERT_TRUE(along.fused_into.has_value());
  EXPECT_FALSE(away.fused_into.has_value());
  for (const Vec2f& p : along.image_points) EXPECT_LE(p.y(), 6.f);
  EXPECT_GE(away.image_points.back().y(), 59.f);
  EXPECT_TRUE(along.image_points.back().isApprox(away.image_points.front()));
  EXPECT_EQ(along.half_widths.size(), 2 * along.segments());
  EXPECT_EQ(away.half_widths.size(), 2 * away.segments());
}

TEST(Fuse, AShortGapInAStretchIsFusedToo) {
  // Along the contour at 3 px, drifting out to 8 px for 20 px, then back: one stretch, drawn once.
  Stroke ridge = joined(straight(LineKind::Ridge, {0, 3}, {40, 3}, 21), straight(LineKind::Ridge, {40, 3}, {45, 8}, 4));
  ridge = joined(ridge, straight(LineKind::Ridge, {45, 8}, {60, 8}, 8));
  ridge = joined(ridge, straight(LineKind::Ridge, {60, 8}, {65, 3}, 4));
  ridge = joined(ridge, straight(LineKind::Ridge, {65, 3}, {100, 3}, 18));
  std::vector<Stroke> in = {straight(LineKind::Contour, {0, 0}, {100, 0}, 51), ridge};
  const FusionResult r = fuse_strokes(in, {FusionRank::Outline, FusionRank::Feature}, kPen);
  ASSERT_EQ(r.strokes.size(), 2u);
  EXPECT_TRUE(r.strokes[1].fused_into.has_value());
  // With gaps not bridged, the part 8 px away is drawn on its own.
  const FusionResult apart =
      fuse_strokes(in, {FusionRank::Outline, FusionRank::Feature}, kPen, {.max_gap_px = 0.f});
  EXPECT_EQ(apart.strokes.size(), 4u);
}

TEST(Fuse, CrossingAndDistantLinesStay) {
  std::vector<Stroke> in = {straight(LineKind::Contour, {0, 0}, {100, 0}, 51),
                            straight(LineKind::Ridge, {50, -50}, {50, 50}, 51),    // crosses
                            straight(LineKind::Valley, {0, 10}, {100, 10}, 51)};  // 10 px away
  const FusionResult r =
      fuse_strokes(in, {FusionRank::Outline, FusionRank::Feature, FusionRank::Feature}, kPen);
  ASSERT_EQ(r.strokes.size(), 3u);
  for (const Stroke& s : r.strokes) EXPECT_FALSE(s.fused_into.has_value());
}

TEST(Fuse, TwoTracingsOfOneRimKeepTheOutline) {
  // An interior contour traced along the outline, longer than it: the outline is drawn.
  std::vector<Stroke> in = {straight(LineKind::Contour, {0, 2}, {140, 2}, 71),
                            straight(LineKind::Contour, {0, 0}, {100, 0}, 51)};
  const FusionResult r = fuse_strokes(in, {FusionRank::Interior, FusionRank::Outline}, kPen);
  bool outline_fused = false, interior_fused = false;
  for (const Stroke& s : r.strokes) {
    if (!s.fused_into) continue;
    (s.image_points.front().y() < 1.f ? outline_fused : interior_fused) = true;
  }
  EXPECT_FALSE(outline_fused);
  EXPECT_TRUE(interior_fused);
}

TEST(Fuse, BetweenEqualRanksTheLongerLineIsDrawn) {
  std::vector<Stroke> in = {straight(LineKind::Ridge, {0, 2}, {50, 2}, 26),
                            straight(LineKind::Ridge, {0, 0}, {100, 0}, 51)};
  const FusionResult r = fuse_strokes(in, {FusionRank::Feature, FusionRank::Feature}, kPen);
  ASSERT_EQ(r.strokes.size(), 2u);
  ASSERT_TRUE(r.strokes[0].fused_into.has_value());
  EXPECT_EQ(*r.strokes[0].fused_into, 1u);
  EXPECT_FALSE(r.strokes[1].fused_into.has_value());
}

TEST(Fuse, HiddenStrokesHatchingAndShortStretchesTakeNoPart) {
  Stroke hidden = straight(LineKind::Ridge, {0, 2}, {100, 2}, 51);
  hidden.visible = false;
  // A ridge 6 px alongside (under 10 px), then away: it touches the contour, it does not double it.
  const Stroke touching =
      joined(straight(LineKind::Ridge, {40, 2}, {46, 2}, 4), straight(LineKind::Ridge, {46, 2}, {50, 40}, 20));
  std::vector<Stroke> in = {straight(LineKind::Contour, {0, 0}, {100, 0}, 51), hidden,
                            straight(LineKind::Hatch, {0, 1}, {100, 1}, 51), touching};
  const FusionResult r = fuse_strokes(
      in, {FusionRank::Outline, FusionRank::Feature, FusionRank::None, FusionRank::Feature}, kPen);
  ASSERT_EQ(r.strokes.size(), 4u);
  for (const Stroke& s : r.strokes) EXPECT_FALSE(s.fused_into.has_value());
}

TEST(Fuse, AShortContourAlongsideOverItsWholeLengthIsADouble) {
  // 6 px long, 1 px (within half a pen width) beside the outline all along: shorter than min_stretch_px, drawn once
  // all the same. Across the outline a stroke stays (the angle test); 3 px away (within the fusion distance, 6 px) it
  // may be a fold beside the outline, and it stays; a ridge as short and as close stays in its layer.
  std::vector<Stroke> in = {
      straight(LineKind::Contour, {0, 0}, {100, 0}, 51), straight(LineKind::Contour, {40, 1}, {46, 1}, 4),
      straight(LineKind::Contour, {70, -3}, {70, 3}, 4), straight(LineKind::Contour, {20, 3}, {26, 3}, 4),
      straight(LineKind::Ridge, {80, 1}, {86, 1}, 4)};
  const FusionResult r = fuse_strokes(
      in, {FusionRank::Outline, FusionRank::Interior, FusionRank::Interior, FusionRank::Interior, FusionRank::Feature},
      kPen);
  ASSERT_EQ(r.strokes.size(), 5u);
  ASSERT_TRUE(r.strokes[1].fused_into.has_value());
  EXPECT_EQ(*r.strokes[1].fused_into, 0u);
  for (std::size_t s = 2; s < 5; ++s) EXPECT_FALSE(r.strokes[s].fused_into.has_value()) << s;
}

TEST(Fuse, DisabledLeavesEveryStroke) {
  std::vector<Stroke> in = {straight(LineKind::Contour, {0, 0}, {100, 0}, 51),
                            straight(LineKind::Ridge, {0, 3}, {100, 3}, 34)};
  const FusionResult r = fuse_strokes(in, {FusionRank::Outline, FusionRank::Feature}, kPen, {.enabled = false});
  ASSERT_EQ(r.strokes.size(), 2u);
  EXPECT_FALSE(r.strokes[1].fused_into.has_value());
  EXPECT_THROW(fuse_strokes(in, {FusionRank::Outline}, kPen), Error);
}

}  // namespace
}  // namespace pcsketch::stylize
