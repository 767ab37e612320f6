// Line finish: smoothing keeps corners and flattens stairs; short strokes are left out.

#include "pcsketch/stylize/line_finish.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pcsketch::stylize {
namespace {

/// The paper's camera (+z view) framing `points` in 1024 × 1024 px.
view::Camera camera_for(const std::vector<Vec3f>& points) { return view::make_camera(points, Vec3d::Zero()); }

TEST(LineFinish, SmoothingKeepsASquaresCorners) {
  // Square [-1, 1]² with 40 vertices a side (about 24 px apart at this framing), closed.
  Polyline square;
  square.closed = true;
  const Vec3f corners[] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < 40; ++k)
      square.points.push_back(corners[side] +
                              (corners[(side + 1) % 4] - corners[side]) * (static_cast<float>(k) / 40.f));
  const Polyline smooth = smooth_line(square, camera_for(square.points));
  ASSERT_EQ(smooth.size(), square.size());
  for (int side = 0; side < 4; ++side) EXPECT_TRUE(smooth.points[40 * side].isApprox(corners[side]));
  // Every vertex stays on the square's outline: straight sides between fixed corners do not move off their line.
  for (const Vec3f& p : smooth.points) {
    const float off = std::min(std::abs(std::abs(p.x()) - 1.f), std::abs(std::abs(p.y()) - 1.f));
    EXPECT_LT(off, 1e-4f);
  }
}

TEST(LineFinish, SmoothingFlattensAStaircase) {
  // A diagonal traced as a staircase: 200 steps of 0.01 (about 9 px at this framing), turning 90° at every step.
  Polyline stairs;
  for (int k = 0; k <= 200; ++k) {
    stairs.points.emplace_back(0.01f * static_cast<float>((k + 1) / 2), 0.01f * static_cast<float>(k / 2), 0.f);
  }
  const view::Camera cam = camera_for(stairs.points);
  const Polyline smooth = smooth_line(stairs, cam);
  // Largest distance (px) from the line the stairs follow (y = x − 0.005, through the middle of every step), away
  // from the two pinned ends.
  auto worst = [&](const Polyline& l) {
    float d = 0.f;
    for (std::size_t i = 10; i + 10 < l.size(); ++i) {
      const Vec2f a = cam.project(l.points[i]).head<2>();
      const Vec2f o = cam.project(Vec3f(0.005f, 0, 0)).head<2>(), e = cam.project(Vec3f(1.005f, 1, 0)).head<2>();
      const Vec2f dir = (e - o).normalized();
      d = std::max(d, std::abs(dir.x() * (a - o).y() - dir.y() * (a - o).x()));
    }
    return d;
  };
  EXPECT_GT(worst(stairs), 1.5f);
  EXPECT_LT(worst(smooth), 0.25f * worst(stairs));
  EXPECT_TRUE(smooth.points.front().isApprox(stairs.points.front()));
  EXPECT_TRUE(smooth.points.back().isApprox(stairs.points.back()));
}

TEST(LineFinish, SparseLinesKeepTheirSamples) {
  // A circle of radius 1 through 40 vertices (about 70 px apart at this framing), one in two pushed out by 2%: the
  // bumps are the shape sampled at those vertices (a coarse cloud's outline), not a zigzag under the pen.
  Polyline ring;
  ring.closed = true;
  for (int k = 0; k < 40; ++k) {
    const float a = 2 * std::numbers::pi_v<float> * static_cast<float>(k) / 40.f, r = k % 2 ? 1.02f : 1.f;
    ring.points.emplace_back(r * std::cos(a), r * std::sin(a), 0.f);
  }
  EXPECT_EQ(smooth_line(ring, camera_for(ring.points)).points, ring.points);
  // The same bumps 4 px apart are smoothed (the stairs of a dense trace).
  Polyline dense = ring;
  for (Vec3f& p : dense.points) p *= 0.05f;
  dense.points.push_back(Vec3f(-2, -2, 0));  // frames the small ring at the same scale
  dense.points.push_back(Vec3f(2, 2, 0));
  const view::Camera cam = camera_for(dense.points);
  dense.points.resize(40);
  EXPECT_NE(smooth_line(dense, cam).points, dense.points);
}

TEST(LineFinish, SmoothingOffLeavesTheLine) {
  Polyline l;
  l.points = {{0, 0, 0}, {1, 0.3f, 0}, {2, -0.2f, 0}, {3, 0, 0}};
  const Polyline same = smooth_line(l, camera_for(l.points), {.smooth = false});
  EXPECT_EQ(same.points, l.points);
}

TEST(LineFinish, LinesSeenOverAFewPixelsAreLeftOut) {
  // Each stroke along x from (x0, y), on rows 20 px apart so that no two meet unless asked to.
  auto stroke = [](float x0, float y, float length, bool visible) {
    Stroke s;
    s.visible = visible;
    s.points = {{x0, y, 0}, {x0 + length, y, 0}};
    s.image_points = {{x0, y}, {x0 + length, y}};
    s.widths = {1, 1};
    s.half_widths = {1, 1};
    return s;
  };
  StrokesResult r;
  // Line 0 seen over 2 px, line 1 hidden, line 2 over 50 px, line 3 over 4.9 px, line 4 over two runs of 3 px,
  // line 5 over 3 px starting 2 px past the end of line 2 (its continuation).
  r.strokes = {stroke(0, 0, 2, true),  stroke(0, 20, 2, false),  stroke(0, 40, 50, true), stroke(0, 60, 4.9f, true),
               stroke(0, 80, 3, true), stroke(3, 80, 40, false), stroke(43, 80, 3, true), stroke(52, 40, 3, true)};
  r.line = {0, 1, 2, 3, 4, 4, 4, 5};
  EXPECT_EQ(drop_short_strokes(r), 2u);  // default 5 px
  ASSERT_EQ(r.strokes.size(), 6u);
  EXPECT_EQ(r.line, (std::vector<std::uint32_t>{1, 2, 4, 4, 4, 5}));
  EXPECT_FALSE(r.strokes[0].visible);
}

}  // namespace
}  // namespace pcsketch::stylize
