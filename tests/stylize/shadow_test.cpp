#include "pcsketch/stylize/shadow.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "pcsketch/core/error.h"
#include "support/analytic_shapes.h"

namespace pcsketch::stylize {
namespace {

/// A cloud with its disc scene (constant local spacing) and camera.
struct Scene {
  PointCloud cloud;
  std::vector<float> spacing;
  float h = 0.f;
  view::SurfaceScene scene;
  view::Camera camera;

  Scene(PointCloud c, float local, float mean_h, const view::CameraOptions& cam)
      : cloud(std::move(c)),
        spacing(cloud.size(), local),
        h(mean_h),
        scene(cloud.positions, cloud.normals, spacing),
        camera(view::make_camera(cloud.positions, cloud.origin, cam)) {}

  ShadowResult shade(const std::vector<Polyline>& lines, const ShadowOptions& o) const {
    static const std::vector<std::vector<std::uint8_t>> kAllVisible;
    return shadow_hatching({.positions = cloud.positions,
                            .normals = cloud.normals,
                            .local_spacing = spacing,
                            .scene = scene,
                            .camera = camera,
                            .spacing = h,
                            .lines = lines,
                            .visible = kAllVisible},
                           o);
  }
};

PointCloud concat(PointCloud a, const PointCloud& b, const Vec3f& shift) {
  for (std::size_t i = 0; i < b.size(); ++i) {
    a.positions.push_back(b.positions[i] + shift);
    a.normals.push_back(b.normals[i]);
  }
  return a;
}

Polyline ridge(const Vec3f& a, const Vec3f& b, int n) {
  Polyline l;
  l.kind = LineKind::Ridge;
  for (int i = 0; i < n; ++i) l.points.push_back(a + (b - a) * (static_cast<float>(i) / static_cast<float>(n - 1)));
  return l;
}

TEST(Light, DefaultIsPaperFig13) {
  // 45° to the xoy plane, parallel to the xoz plane, travelling toward +z (the sight) and −x.
  const Vec3f l = light_direction({}, view::Camera{});
  EXPECT_NEAR(l.x(), -std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(l.y(), 0.f, 1e-6f);
  EXPECT_NEAR(l.z(), std::sqrt(0.5f), 1e-6f);
  EXPECT_TRUE(light_direction({.direction = Vec3f(0, 0, -2)}, view::Camera{}).isApprox(Vec3f(0, 0, -1)));
  EXPECT_THROW(light_direction({.direction = Vec3f::Zero()}, view::Camera{}), Error);
  // Following the camera: a camera looking along −x sees the light as the paper's camera sees the default.
  view::Camera side;
  side.forward = Vec3f(-1, 0, 0);
  side.up = Vec3f(0, 1, 0);
  side.right = side.forward.cross(side.up);
  const Vec3f f = light_direction({.follow_camera = true}, side);
  EXPECT_NEAR(f.dot(side.forward), std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(f.dot(side.right), std::sqrt(0.5f), 1e-6f);
}

TEST(AttachedShadow, SphereHatchedOnlyAwayFromLight) {
  const Scene s(test::sphere(1.f, {.n = 20000}), 0.05f, 0.025f, {.width = 400, .height = 400});
  const ShadowOptions o{.mode = ShadowMode::Attached, .light = {.direction = Vec3f(-1, 0, 0)}};
  const ShadowResult r = s.shade({}, o);
  ASSERT_GT(r.strokes.size(), 20u);
  EXPECT_TRUE(r.regions.empty());
  const Vec3f centre = s.camera.project(Vec3f::Zero());
  const float radius_px = s.camera.scale;
  float length = 0.f;
  for (const Stroke& st : r.strokes) {
    EXPECT_EQ(st.kind, LineKind::Hatch);
    ASSERT_EQ(st.points.size(), 2u);
    length += (st.image_points[1] - st.image_points[0]).norm();
    for (std::size_t i = 0; i < 2; ++i) {
      // On the front of the sphere, on its −x half (n·l > 0 with l = −x), inside the silhouette.
      EXPECT_LT(st.points[i].x(), 0.06f);
      EXPECT_NEAR(st.points[i].norm(), 1.f, 0.05f);
      EXPECT_LT((st.image_points[i] - centre.head<2>()).norm(), radius_px + 2.f);
    }
  }
  // The shadowed half disc is filled: total hatch length near its area / spacing (π r²/2 / 6 px), cross-hatched part
  // included, so well above the single-family estimate's half.
  const float half_disc = 0.5f * 3.14159265f * radius_px * radius_px;
  EXPECT_GT(length, 0.5f * half_disc / o.hatch_spacing_px);
}

TEST(AttachedShadow, PlaneFacingTheLightHasNone) {
  const Scene s(test::plane(1.f, {.n = 20000}), 0.03f, 0.014f,
                {.direction = Vec3d(0, 0, -1), .width = 400, .height = 400});
  for (ShadowMode mode : {ShadowMode::Attached, ShadowMode::Both, ShadowMode::Paper}) {
    const ShadowResult r = s.shade({}, {.mode = mode, .light = {.direction = Vec3f(0.3f, 0.2f, -1)}});
    EXPECT_TRUE(r.strokes.empty());
    EXPECT_TRUE(r.regions.empty());
  }
  // The same plane lit from behind is all attached shadow.
  const ShadowResult back = s.shade({}, {.mode = ShadowMode::Attached, .light = {.direction = Vec3f(0, 0, 1)}});
  EXPECT_GT(back.strokes.size(), 50u);
}

TEST(PaperShadow, RidgeAbovePlaneCastsGradedHatching) {
  // A ridge line at height 0.2 above the plane z = 0, lit along (1, 0, −1): its shadow falls at x = 0.2.
  const Scene s(test::plane(1.f, {.n = 20000}), 0.03f, 0.014f,
                {.direction = Vec3d(0, 0, -1), .width = 400, .height = 400});
  const std::vector<Polyline> lines = {ridge({0, -0.5f, 0.2f}, {0, 0.5f, 0.2f}, 41)};
  const ShadowOptions o{.mode = ShadowMode::Paper, .light = {.direction = Vec3f(1, 0, -1)}};
  const ShadowResult r = s.shade(lines, o);
  EXPECT_EQ(r.casting_candidates, 41u);
  EXPECT_EQ(r.cast_vertices, 41u);
  // One unbroken hatch stroke per k, at t = k·d = 1/8, 1/4, 1/2, 1 of the way to the projection, on the far side.
  ASSERT_EQ(r.strokes.size(), 4u);
  const float ts[] = {0.125f, 0.25f, 0.5f, 1.f};
  for (std::size_t j = 0; j < 4; ++j) {
    const Stroke& st = r.strokes[j];
    EXPECT_EQ(st.kind, LineKind::Hatch);
    EXPECT_EQ(st.points.size(), 41u);
    for (const Vec3f& p : st.points) {
      EXPECT_NEAR(p.x(), 0.2f * ts[j], 1e-4f);
      EXPECT_NEAR(p.z(), 0.2f * (1 - ts[j]), 1e-4f);
    }
    if (j > 0) {
      EXPECT_GT(st.grey, r.strokes[j - 1].grey);                                // lighter away from the line
      EXPECT_GT(st.image_points[0].x(), r.strokes[j - 1].image_points[0].x());  // image +u is +x here
    }
  }
  // Blocks between the line and the first hatch line, and between successive hatch lines: darker near the line.
  ASSERT_EQ(r.regions.size(), 4u);
  float prev_u = -1e9f;
  for (std::size_t j = 0; j < 4; ++j) {
    if (j > 0) {
      EXPECT_GT(r.regions[j].grey, r.regions[j - 1].grey);
    }
    float u = 0.f;
    for (const Vec2f& q : r.regions[j].polygon) u += q.x();
    u /= static_cast<float>(r.regions[j].polygon.size());
    EXPECT_GT(u, prev_u);
    prev_u = u;
  }
}

TEST(PaperShadow, MissesAndOccludersBreakHatching) {
  // The line runs past the plane's edge (y > 1: the light ray misses), and a floating patch at z = 0.5 over
  // x ∈ [0.15, 0.65], |y| ≤ 0.25 hides the outermost hatch line (x = 0.2) from the viewer above.
  const PointCloud cloud =
      concat(test::plane(1.f, {.n = 20000}), test::plane(0.25f, {.n = 1500, .seed = 7}), Vec3f(0.4f, 0, 0.5f));
  const Scene s(cloud, 0.03f, 0.014f, {.direction = Vec3d(0, 0, -1), .width = 400, .height = 400});
  const std::vector<Polyline> lines = {ridge({0, -0.5f, 0.2f}, {0, 1.5f, 0.2f}, 81)};
  const ShadowResult r = s.shade(lines, {.mode = ShadowMode::Paper, .light = {.direction = Vec3f(1, 0, -1)}});
  EXPECT_LT(r.cast_vertices, 81u);
  EXPECT_GT(r.cast_vertices, 35u);
  int outer = 0;
  for (const Stroke& st : r.strokes)
    for (const Vec3f& p : st.points) {
      EXPECT_LE(p.y(), 1.03f);
      if (std::abs(p.x() - 0.2f) < 1e-3f) {
        ++outer;
        EXPECT_GT(std::abs(p.y()), 0.2f);  // hidden under the patch
      }
    }
  EXPECT_GT(outer, 10);
}

// A ridge in the air above empty space casting onto a small patch: the region between them is seen against the
// background, except where it reaches the patch. Clipped to the surface, only the hatch line on the patch is drawn;
// the paper's region draws all four over the background.
TEST(PaperShadow, RegionOverTheBackgroundIsNotDrawn) {
  const PointCloud patch = concat(PointCloud{}, test::plane(0.15f, {.n = 3000, .seed = 9}), Vec3f(0.5f, 0, 0));
  // h = 0.01 puts the hit (0.71 away along the light) within max_cast_factor · h.
  const Scene s(patch, 0.012f, 0.01f, {.direction = Vec3d(0, 0, -1), .width = 400, .height = 400});
  const std::vector<Polyline> lines = {ridge({0, -0.1f, 0.5f}, {0, 0.1f, 0.5f}, 21)};
  const ShadowOptions clipped{.mode = ShadowMode::Paper, .light = {.direction = Vec3f(1, 0, -1)}};
  const ShadowResult r = s.shade(lines, clipped);
  EXPECT_EQ(r.cast_vertices, 21u);
  ASSERT_EQ(r.strokes.size(), 1u);
  for (const Vec3f& p : r.strokes[0].points) EXPECT_NEAR(p.x(), 0.5f, 1e-4f);
  EXPECT_TRUE(r.regions.empty());  // every block has an edge over the background

  ShadowOptions paper = clipped;
  paper.clip_to_surface = false;
  const ShadowResult unclipped = s.shade(lines, paper);
  EXPECT_EQ(unclipped.strokes.size(), 4u);
  EXPECT_EQ(unclipped.regions.size(), 4u);
}

TEST(PaperShadow, LitRidgeOnSphereCastsNothing) {
  // A ridge circle on the sphere's lit cap: rays along the light enter the sphere and meet its far side from inside.
  const Scene s(test::sphere(1.f, {.n = 20000}), 0.05f, 0.025f, {.width = 400, .height = 400});
  Polyline l;
  l.kind = LineKind::Ridge;
  l.closed = true;
  for (int i = 0; i < 60; ++i) {
    const float a = static_cast<float>(i) * 2 * 3.14159265f / 60;
    l.points.push_back(Vec3f(0.8f, 0.6f * std::cos(a), 0.6f * std::sin(a)));
  }
  const ShadowResult r = s.shade({l}, {.mode = ShadowMode::Paper, .light = {.direction = Vec3f(-1, 0, 0)}});
  EXPECT_EQ(r.casting_candidates, 60u);
  EXPECT_EQ(r.cast_vertices, 0u);
  EXPECT_TRUE(r.strokes.empty());
}

TEST(Shadow, SameResultForAnyThreadCount) {
  const PointCloud cloud = concat(test::plane(1.f, {.n = 20000}), test::sphere(0.3f, {.n = 8000}), Vec3f(0, 0, 0.3f));
  const Scene s(cloud, 0.03f, 0.014f, {.direction = Vec3d(0.2, 0.1, -1), .width = 300, .height = 300});
  const std::vector<Polyline> lines = {ridge({-0.5f, -0.5f, 0.25f}, {0.5f, 0.5f, 0.25f}, 60)};
  const ShadowOptions o{.mode = ShadowMode::Both, .light = {.direction = Vec3f(1, 0.3f, -1)}};
  const ShadowResult many = s.shade(lines, o);
  ShadowResult one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = s.shade(lines, o);
  }
  ASSERT_GT(many.strokes.size(), 10u);
  ASSERT_EQ(many.strokes.size(), one.strokes.size());
  ASSERT_EQ(many.regions.size(), one.regions.size());
  for (std::size_t i = 0; i < many.strokes.size(); ++i) {
    ASSERT_EQ(many.strokes[i].image_points.size(), one.strokes[i].image_points.size());
    for (std::size_t j = 0; j < many.strokes[i].image_points.size(); ++j)
      EXPECT_EQ(many.strokes[i].image_points[j], one.strokes[i].image_points[j]);
  }
}

TEST(Shadow, RejectsMismatchedInput) {
  const Scene s(test::sphere(1.f, {.n = 2000}), 0.1f, 0.08f, {.width = 100, .height = 100});
  const std::vector<float> short_spacing(10, 0.1f);
  const std::vector<Polyline> lines;
  const std::vector<std::vector<std::uint8_t>> vis;
  EXPECT_THROW(shadow_hatching({.positions = s.cloud.positions,
                                .normals = s.cloud.normals,
                                .local_spacing = short_spacing,
                                .scene = s.scene,
                                .camera = s.camera,
                                .spacing = 0.08f,
                                .lines = lines,
                                .visible = vis}),
               Error);
  const std::vector<Vec3f> none;
  const std::vector<float> no_spacing;
  const ShadowResult empty = shadow_hatching({.positions = none,
                                              .normals = none,
                                              .local_spacing = no_spacing,
                                              .scene = s.scene,
                                              .camera = s.camera,
                                              .spacing = 0.f,
                                              .lines = lines,
                                              .visible = vis});
  EXPECT_TRUE(empty.strokes.empty());
  EXPECT_EQ(empty.warnings.size(), 1u);
  EXPECT_NO_THROW(shadow_hatching({.positions = s.cloud.positions,
                                   .normals = s.cloud.normals,
                                   .local_spacing = short_spacing,
                                   .scene = s.scene,
                                   .camera = s.camera,
                                   .spacing = 0.08f,
                                   .lines = lines,
                                   .visible = vis},
                                  {.mode = ShadowMode::None}));
}

}  // namespace
}  // namespace pcsketch::stylize
