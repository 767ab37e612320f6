#include "pcsketch/stylize/thickness.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pcsketch/core/error.h"

namespace pcsketch::stylize {
namespace {

Polyline straight(const Vec3f& a, const Vec3f& b, int n, LineKind kind = LineKind::Contour) {
  Polyline l;
  l.kind = kind;
  for (int i = 0; i < n; ++i) l.points.push_back(a + (b - a) * (static_cast<float>(i) / static_cast<float>(n - 1)));
  return l;
}

std::vector<Vec3f> all_points(const std::vector<Polyline>& lines) {
  std::vector<Vec3f> p;
  for (const Polyline& l : lines) p.insert(p.end(), l.points.begin(), l.points.end());
  return p;
}

float mean(const std::vector<float>& v) {
  float s = 0;
  for (float x : v) s += x;
  return s / static_cast<float>(v.size());
}

TEST(Thickness, NearerLineIsThicker) {
  // Two equal lines, one at depth z = 0 (near: the default camera looks along +z), one at z = 1.
  const std::vector<Polyline> lines = {straight({-1, 0, 0}, {1, 0, 0}, 20), straight({-1, 0.5f, 1}, {1, 0.5f, 1}, 20)};
  const view::Camera cam = view::make_camera(all_points(lines), Vec3d::Zero());
  for (ThicknessModel model : {ThicknessModel::Depth, ThicknessModel::Combined}) {
    const auto r = make_strokes(lines, cam, {}, {.model = model, .brush = false});
    ASSERT_EQ(r.strokes.size(), 2u);
    EXPECT_GT(mean(r.strokes[0].widths), mean(r.strokes[1].widths) + 0.5f);
  }
  // Pure depth model: the extremes of the drawing's depth range get exactly ρ_max and ρ_min.
  const auto r =
      make_strokes(lines, cam, {}, {.model = ThicknessModel::Depth, .rho_min = 1, .rho_max = 4, .brush = false});
  EXPECT_NEAR(r.depth_range.far - r.depth_range.near, 1.f, 1e-5f);
  for (float w : r.strokes[0].widths) EXPECT_NEAR(w, 4.f, 1e-4f);
  for (float w : r.strokes[1].widths) EXPECT_NEAR(w, 1.f, 1e-4f);
}

TEST(Thickness, SharperBendIsThicker) {
  // A right-angle corner at vertex 10 and a gentler 135° bend at vertex 30, in the image plane (z = 0).
  Polyline l;
  for (int i = 0; i <= 10; ++i) l.points.emplace_back(0.1f * static_cast<float>(i), 0, 0);
  for (int i = 1; i <= 20; ++i) l.points.emplace_back(1, 0.1f * static_cast<float>(i), 0);
  const float turn = 45.f * 3.14159265f / 180.f;  // the path turns by 45°: interior angle 135°
  for (int i = 1; i <= 10; ++i)
    l.points.emplace_back(1 - 0.1f * std::sin(turn) * static_cast<float>(i),
                          2 + 0.1f * std::cos(turn) * static_cast<float>(i), 0);
  const view::Camera cam = view::make_camera(l.points, Vec3d::Zero());
  for (float arm : {0.f, 6.f}) {
    const auto r = make_strokes({l}, cam, {}, {.model = ThicknessModel::Angle, .angle_arm_px = arm, .brush = false});
    ASSERT_EQ(r.strokes.size(), 1u);
    const std::vector<float>& w = r.strokes[0].widths;
    EXPECT_GT(w[10], w[30]) << "arm " << arm;
    EXPECT_GT(w[30], w[20]) << "arm " << arm;  // straight part: thinnest
  }
  // Paper's neighbours: 90° is level 4, 135° level 2 → widths 4/10 and 2/10 of ρ_max in the Paper mapping.
  const auto r = make_strokes({l}, cam, {},
                              {.model = ThicknessModel::Angle,
                               .rho_max = 3,
                               .angle_arm_px = 0,
                               .angle_width = AngleWidth::Paper,
                               .brush = false});
  EXPECT_NEAR(r.strokes[0].widths[10], 1.2f, 1e-5f);
  EXPECT_NEAR(r.strokes[0].widths[30], 0.6f, 1e-5f);
}

TEST(Thickness, CombinationRules) {
  // A right angle (level 4) at the near end of an explicit depth range: t_depth = ρ_max, t_angle = ρ_min + 3/9·span.
  Polyline l;
  l.points = {{-1, 0, 0}, {0, 0, 0}, {0, 1, 0}};
  const view::Camera cam = view::make_camera(l.points, Vec3d::Zero());
  const float z = cam.project(l.points[1]).z();
  ThicknessOptions o{.model = ThicknessModel::Combined,
                     .rho_min = 1,
                     .rho_max = 4,
                     .angle_arm_px = 0,
                     .depth_range = DepthRange{z, z + 1},
                     .brush = false};
  const float t_angle = 1.f + 3.f / 9.f * 3.f;
  EXPECT_NEAR(make_strokes({l}, cam, {}, o).strokes[0].widths[1], 0.5f * (4.f + t_angle), 1e-5f);
  o.angle_weight = 0.25f;
  EXPECT_NEAR(make_strokes({l}, cam, {}, o).strokes[0].widths[1], 0.75f * 4.f + 0.25f * t_angle, 1e-5f);
  o.combination = Combination::Product;
  EXPECT_NEAR(make_strokes({l}, cam, {}, o).strokes[0].widths[1], 4.f * t_angle / 4.f, 1e-5f);
  // Ends of an open line count as straight (level 1 = ρ_min).
  EXPECT_NEAR(make_strokes({l}, cam, {}, o).strokes[0].widths[0], 4.f * 1.f / 4.f, 1e-5f);
  EXPECT_THROW(make_strokes({l}, cam, {}, {.rho_min = 3, .rho_max = 1}), Error);
}

TEST(Thickness, AngleLevelsAtTable1BinEdges) {
  // Bins are closed on the right: the edge itself belongs to the sharper (higher) level.
  const double edges[] = {20, 30, 40, 50, 60, 80, 100, 120, 150, 180};
  for (int b = 0; b < 10; ++b) {
    EXPECT_EQ(angle_level(edges[b]), 10 - b) << edges[b];
    EXPECT_EQ(angle_level(std::nextafter(edges[b], 0.0)), 10 - b) << edges[b];
    if (b < 9) {
      EXPECT_EQ(angle_level(std::nextafter(edges[b], 200.0)), 9 - b) << edges[b];
    }
  }
  EXPECT_EQ(angle_level(0.0), 10);
  EXPECT_EQ(angle_level(1e-9), 10);
}

TEST(Thickness, HalfSegmentRuleExactValues) {
  // Raw eqs. 4–5: (t_front + t_p/2) and (t_front/2 + t_p).
  const std::vector<float> w = {1.f, 2.f, 4.f};
  const std::vector<float> raw = half_segment_widths(w, false, false);
  ASSERT_EQ(raw.size(), 4u);
  EXPECT_FLOAT_EQ(raw[0], 2.f);
  EXPECT_FLOAT_EQ(raw[1], 2.5f);
  EXPECT_FLOAT_EQ(raw[2], 4.f);
  EXPECT_FLOAT_EQ(raw[3], 5.f);
  // Normalised by 2/3: equal ends keep their width; the mean of the two halves is the mean of the ends.
  const std::vector<float> norm = half_segment_widths(w, false, true);
  EXPECT_FLOAT_EQ(norm[0], 4.f / 3.f);
  EXPECT_FLOAT_EQ(norm[1], 5.f / 3.f);
  EXPECT_FLOAT_EQ(0.5f * (norm[2] + norm[3]), 3.f);
  const std::vector<float> flat = half_segment_widths({2.5f, 2.5f}, false, true);
  EXPECT_FLOAT_EQ(flat[0], 2.5f);
  EXPECT_FLOAT_EQ(flat[1], 2.5f);
  // A closed line has a closing segment 4 → 1: (4 + 1/2) and (4/2 + 1).
  const std::vector<float> closed = half_segment_widths(w, true, false);
  ASSERT_EQ(closed.size(), 6u);
  EXPECT_FLOAT_EQ(closed[4], 4.5f);
  EXPECT_FLOAT_EQ(closed[5], 3.f);
}

TEST(Thickness, CofiScalesAndStrokesCarryHalves) {
  const std::vector<Polyline> lines = {straight({-1, 0, 0}, {1, 0, 0}, 5)};
  const view::Camera cam = view::make_camera(all_points(lines), Vec3d::Zero());
  const auto r = make_strokes(
      lines, cam, {}, {.model = ThicknessModel::Constant, .rho_min = 1, .rho_max = 3, .cofi = 1.5f, .brush = false});
  const Stroke& s = r.strokes[0];
  ASSERT_EQ(s.half_widths.size(), 2 * s.segments());
  for (float w : s.widths) EXPECT_FLOAT_EQ(w, 3.f);  // (1 + 3)/2 · 1.5
  for (float h : s.half_widths) EXPECT_FLOAT_EQ(h, 3.f);
}

TEST(Thickness, BrushTapersEnds) {
  const std::vector<Polyline> lines = {straight({-1, 0, 0}, {1, 0, 0}, 201)};
  const view::Camera cam = view::make_camera(all_points(lines), Vec3d::Zero());
  const ThicknessOptions o{.model = ThicknessModel::Constant,
                           .rho_min = 2,
                           .rho_max = 2,
                           .brush = true,
                           .brush_taper_px = 20,
                           .brush_end_fraction = 0.25f};
  const StrokesResult r = make_strokes(lines, cam, {}, o);
  const std::vector<float>& w = r.strokes[0].widths;
  EXPECT_FLOAT_EQ(w.front(), 0.5f);
  EXPECT_FLOAT_EQ(w.back(), 0.5f);
  EXPECT_FLOAT_EQ(w[100], 2.f);
  // Monotone ramp over the first 20 px (vertices are about 4.6 px apart at the default framing).
  EXPECT_LT(w[1], w[2]);
  EXPECT_LT(w[2], w[3]);
  EXPECT_FLOAT_EQ(w[10], 2.f);
  // A closed line has no ends: no taper.
  Polyline loop = straight({-1, 0, 0}, {1, 0, 0}, 20);
  loop.points.emplace_back(0, 1, 0);
  loop.closed = true;
  const StrokesResult rl = make_strokes({loop}, cam, {}, o);
  for (float x : rl.strokes[0].widths) EXPECT_FLOAT_EQ(x, 2.f);
}

TEST(Thickness, WidthsIndependentOfCloudScale) {
  // A wavy 3D line with depth variation, and the same scaled ×1000; the camera frames each the same way.
  Polyline a;
  for (int i = 0; i < 200; ++i) {
    const float t = static_cast<float>(i) * 0.05f;
    a.points.emplace_back(t, std::sin(3 * t), std::cos(2 * t));
  }
  Polyline b = a;
  for (Vec3f& p : b.points) p *= 1000.f;
  const view::Camera ca = view::make_camera(a.points, Vec3d::Zero());
  const view::Camera cb = view::make_camera(b.points, Vec3d::Zero());
  const auto ra = make_strokes({a}, ca);
  const auto rb = make_strokes({b}, cb);
  ASSERT_EQ(ra.strokes.size(), 1u);
  ASSERT_EQ(rb.strokes.size(), 1u);
  for (std::size_t i = 0; i < ra.strokes[0].widths.size(); ++i)
    EXPECT_NEAR(ra.strokes[0].widths[i], rb.strokes[0].widths[i], 1e-3f) << i;
  for (std::size_t i = 0; i < ra.strokes[0].half_widths.size(); ++i)
    EXPECT_NEAR(ra.strokes[0].half_widths[i], rb.strokes[0].half_widths[i], 1e-3f) << i;
}

TEST(Thickness, ArcLengthAngleIgnoresPointNoise) {
  // A straight line in the image with 0.5 px jitter on vertices 1 px apart: the paper's immediate-neighbour angle
  // finds sharp bends everywhere, the 6 px arm finds a straight line.
  Polyline l;
  std::mt19937 rng(12111);
  std::normal_distribution<float> jitter(0.f, 0.5f);
  for (int i = 0; i < 300; ++i) l.points.emplace_back(static_cast<float>(i), jitter(rng), 0);
  view::Camera cam;  // scale 1: one model unit per pixel
  std::vector<Vec2f> image;
  for (const Vec3f& p : l.points) image.push_back(cam.project(p).head<2>());
  int sharp_paper = 0, sharp_arm = 0;
  const std::vector<float> paper = bend_angles_deg(l, image, 0.f), arm = bend_angles_deg(l, image, 6.f);
  for (std::size_t i = 0; i < l.size(); ++i) {
    sharp_paper += angle_level(paper[i]) >= 3;
    sharp_arm += angle_level(arm[i]) >= 3;
  }
  EXPECT_GT(sharp_paper, 20);
  EXPECT_EQ(sharp_arm, 0);
}

TEST(Thickness, VisibilityRunsShareMidpoints) {
  Polyline l = straight({0, 0, 0}, {4, 0, 0}, 5);
  const view::Camera cam = view::make_camera(l.points, Vec3d::Zero());
  const auto r = make_strokes({l}, cam, {{1, 1, 0, 0, 1}});
  ASSERT_EQ(r.strokes.size(), 3u);
  EXPECT_TRUE(r.strokes[0].visible);
  EXPECT_FALSE(r.strokes[1].visible);
  EXPECT_TRUE(r.strokes[2].visible);
  EXPECT_EQ(r.strokes[0].points.size(), 3u);  // 0, 1, mid(1, 2)
  EXPECT_EQ(r.strokes[1].points.size(), 4u);  // mid(1, 2), 2, 3, mid(3, 4)
  EXPECT_EQ(r.strokes[2].points.size(), 2u);  // mid(3, 4), 4
  EXPECT_TRUE(r.strokes[0].points.back().isApprox(Vec3f(1.5f, 0, 0)));
  EXPECT_TRUE(r.strokes[1].points.front().isApprox(Vec3f(1.5f, 0, 0)));
  EXPECT_TRUE(r.strokes[2].points.front().isApprox(Vec3f(3.5f, 0, 0)));
  for (const Stroke& s : r.strokes) {
    EXPECT_EQ(s.image_points.size(), s.points.size());
    EXPECT_EQ(s.half_widths.size(), 2 * s.segments());
  }
  // A closed loop hidden on one side gives one visible and one hidden stroke meeting at both midpoints.
  Polyline loop;
  for (int i = 0; i < 8; ++i) {
    const float a = static_cast<float>(i) * 3.14159265f / 4.f;
    loop.points.emplace_back(std::cos(a), std::sin(a), 0);
  }
  loop.closed = true;
  const auto rl = make_strokes({loop}, cam, {{1, 1, 1, 0, 0, 0, 0, 1}});
  ASSERT_EQ(rl.strokes.size(), 2u);
  EXPECT_EQ(rl.strokes[0].points.size() + rl.strokes[1].points.size(), 8u + 4u);
  EXPECT_TRUE(rl.strokes[0].points.front().isApprox(rl.strokes[1].points.back()));
  EXPECT_TRUE(rl.strokes[0].points.back().isApprox(rl.strokes[1].points.front()));
  EXPECT_THROW(make_strokes({l}, cam, {{1, 0}}), Error);
}

}  // namespace
}  // namespace pcsketch::stylize
