#include "pcsketch/view/contours.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "pcsketch/core/error.h"
#include "support/analytic_shapes.h"
#include "view/view_test_support.h"

namespace pcsketch::view {
namespace {

using testing::Analysed;

/// Largest distance (pixels) of a contour's vertices from the circle of `radius_px` around `centre`.
float max_circle_error(const ViewLine& line, const Vec2f& centre, float radius_px) {
  float worst = 0;
  for (const Vec3f& q : line.projected) worst = std::max(worst, std::abs((q.head<2>() - centre).norm() - radius_px));
  return worst;
}

std::vector<const ViewLine*> contours_of(const ViewResult& view) {
  std::vector<const ViewLine*> out;
  for (std::size_t i = 0; i < view.contour_count; ++i) out.push_back(&view.lines[i]);
  return out;
}

/// The view of a unit sphere at the origin has one contour, closed, within `tolerance_px` of the projected circle.
const ViewLine& expect_one_closed_circle(const ViewResult& view, float tolerance_px) {
  const auto contours = contours_of(view);
  EXPECT_EQ(contours.size(), 1u);
  if (contours.empty()) throw std::runtime_error("no contour");
  EXPECT_TRUE(contours[0]->line.closed);
  const Vec3f centre = view.camera.project(Vec3f::Zero());
  EXPECT_LT(max_circle_error(*contours[0], centre.head<2>(), view.camera.scale), tolerance_px);
  return *contours[0];
}

TEST(Contours, SphereHasOneClosedContourOnTheProjectedCircle) {
  const Analysed sphere(test::sphere(1.f, {.n = 30000}));
  const ViewResult view = sphere.view({.width = 1024, .height = 1024});
  const ViewLine& contour = expect_one_closed_circle(view, 1.f);
  EXPECT_GT(contour.line.size(), 100u);
  // The outline of a convex body is seen everywhere.
  for (const std::uint8_t v : contour.visible) EXPECT_EQ(v, 1);
}

TEST(Contours, PaperDirectionGuidedRuleAlsoClosesTheSphere) {
  const Analysed sphere(test::sphere(1.f, {.n = 30000}));
  expect_one_closed_circle(sphere.view({}, {}, {.contours = {.connection = OutlineConnection::DirectionGuided}}), 3.f);
}

// A sphere whose density falls smoothly from the top to the bottom, 9× (spacing 3×), as on mesh vertices: the
// outline's lengths follow the local spacing, so the sparse bottom closes like the dense top. At the global h (the
// paper's single radius) the sparse points read as holes: measured, a fragment inside the disc and a 5 px error.
TEST(Contours, UnevenSamplingKeepsTheOutlineClosed) {
  const PointCloud dense = test::sphere(1.f, {.n = 60000, .seed = 31});
  PointCloud cloud;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  for (std::size_t i = 0; i < dense.size(); ++i) {
    const float t = 0.5f * (dense.positions[i].y() + 1.f);
    if (uniform(rng) < 1.f / 9.f + (8.f / 9.f) * t * t) {
      cloud.positions.push_back(dense.positions[i]);
      cloud.normals.push_back(dense.normals[i]);
    }
  }
  const Analysed sphere(std::move(cloud));
  expect_one_closed_circle(sphere.view({.width = 1024, .height = 1024}), 2.f);

  const ViewResult paper = sphere.view({.width = 1024, .height = 1024}, {}, {.contours = {.adaptive_spacing = false}});
  const auto pieces = contours_of(paper);
  ASSERT_FALSE(pieces.empty());
  const Vec3f centre = paper.camera.project(Vec3f::Zero());
  EXPECT_TRUE(pieces.size() > 1 || max_circle_error(*pieces[0], centre.head<2>(), paper.camera.scale) > 2.f)
      << "the global h traces the sparse half as well";
}

TEST(Contours, PerspectiveSphereOutlineIsTheConeTangentCircle) {
  const Analysed sphere(test::sphere(1.f, {.n = 30000}));
  const ViewResult view = sphere.view(
      {.projection = Projection::Perspective, .eye = Vec3d(0, 0, -4), .target = Vec3d::Zero(), .fov_deg = 40.0});
  const auto contours = contours_of(view);
  ASSERT_EQ(contours.size(), 1u);
  EXPECT_TRUE(contours[0]->line.closed);
  // The rays tangent to the sphere make a cone of half-angle asin(1/4) around the axis to the centre.
  const float radius_px = view.camera.scale * std::tan(std::asin(0.25f));
  EXPECT_LT(max_circle_error(*contours[0], view.camera.principal, radius_px), 1.f);
}

TEST(Contours, TorusAlongItsAxisHasRimAndHole) {
  const float R = 1.f, r = 0.35f;
  const Analysed torus(test::torus(R, r, {.n = 30000}));
  const ViewResult view = torus.view({.direction = Vec3d(0, 0, 1)});
  const auto contours = contours_of(view);
  ASSERT_EQ(contours.size(), 2u);
  const Vec2f centre = view.camera.project(Vec3f::Zero()).head<2>();
  std::vector<float> radii;
  for (const ViewLine* c : contours) {
    EXPECT_TRUE(c->line.closed);
    float mean = 0;
    for (const Vec3f& q : c->projected) mean += (q.head<2>() - centre).norm();
    radii.push_back(mean / static_cast<float>(c->projected.size()));
  }
  std::sort(radii.begin(), radii.end());
  EXPECT_NEAR(radii[0], (R - r) * view.camera.scale, 2.f);
  EXPECT_NEAR(radii[1], (R + r) * view.camera.scale, 2.f);
}

// Points found without the bending test (ContourPoints::rim_bends empty), then connected as a denoised cloud's: the
// rule on the share of samples that bend needs the bends, so it stays out, and the interior contours are the clean
// rule's that reach denoised_min_length_factor. Seen nearly edge-on, the torus's tube hides part of itself.
TEST(Contours, DenoisedConnectionWithoutBendsKeepsTheLongInteriorContours) {
  const Analysed torus(test::torus(1.f, 0.35f, {.n = 30000}));
  const Camera camera = make_camera(torus.cloud.positions, torus.cloud.origin, {.direction = Vec3d(0, 1, 0.3)});
  const float h = torus.surface.spacing;
  const ContourOptions o;
  const ContourPoints cp =
      find_contour_points(torus.cloud.positions, torus.cloud.normals, torus.surface.neighbourhoods, h, camera, o);
  ASSERT_TRUE(cp.rim_bends.empty());
  const auto lengths = [&](bool denoised, float at_least) {
    std::vector<float> out;
    for (const Polyline& line : connect_contours(cp, torus.cloud.positions, h, o, denoised).interior)
      if (line.length() >= at_least) out.push_back(line.length());
    std::sort(out.begin(), out.end());
    return out;
  };
  const std::vector<float> long_clean = lengths(false, o.denoised_min_length_factor * h);
  ASSERT_FALSE(long_clean.empty());
  EXPECT_EQ(lengths(true, 0.f), long_clean);
}

// A tube seen along its axis: its whole side projects onto one circle, hundreds of points per pixel of it (as a CAD
// part's faces along a front view). One point per quarter-spacing image cell is asked, and the outline is still
// the circle, closed and within a pixel.
TEST(Contours, TubeAlongItsAxisHasItsCircleAsOutline) {
  const Analysed tube(test::cylinder(1.f, 2.f, {.n = 60000, .seed = 3}));
  const ViewResult view = tube.view({.direction = Vec3d(0, 0, 1)});
  expect_one_closed_circle(view, 1.f);
}

// A sphere whose normals point inward on a cap, as where a sheet's two sides or a plate's merged faces leave the
// orientation's signs flipped in patches: across the cap's border, neighbouring normals are nearly opposite and n·v
// changes sign firmly. That border is no rim, so it makes no rim sample; the real rim, turning the normal through
// the view plane, still does (180°, the rule off, samples the border too).
TEST(Contours, OppositeNormalsMakeNoRimSamples) {
  Analysed sphere(test::sphere(1.f, {.n = 30000}));
  // The cap x > 0.5 faces the viewer (looking along -x); its border is a circle of radius 0.87 around the x axis.
  for (std::size_t i = 0; i < sphere.cloud.size(); ++i)
    if (sphere.cloud.positions[i].x() > 0.5f) sphere.cloud.normals[i] = -sphere.cloud.normals[i];
  const Camera camera = make_camera(sphere.cloud.positions, sphere.cloud.origin, {.direction = Vec3d(-1, 0, 0)});
  const auto samples_near = [&](const ContourPoints& cp, float x) {
    std::size_t count = 0;
    for (const Vec3f& r : cp.rim) count += std::abs(r.x() - x) < 0.05f ? 1 : 0;
    return count;
  };
  const auto find = [&](float angle) {
    ContourOptions o;
    o.interior_max_normal_angle_deg = angle;
    return find_contour_points(sphere.cloud.positions, sphere.cloud.normals, sphere.surface.neighbourhoods,
                               sphere.surface.spacing, camera, o);
  };
  const ContourPoints kept = find(ContourOptions{}.interior_max_normal_angle_deg), all = find(180.f);
  EXPECT_GT(samples_near(all, 0.5f), 300u);
  EXPECT_EQ(samples_near(kept, 0.5f), 0u);
  EXPECT_GT(samples_near(kept, 0.f), 300u);  // the rim, the great circle x = 0
  EXPECT_EQ(samples_near(kept, 0.f), samples_near(all, 0.f));
}

TEST(Contours, RejectsNonPositiveSpacing) {
  const PointCloud s = test::sphere(1.f, {.n = 100});
  const Camera camera = make_camera(s.positions, s.origin);
  EXPECT_THROW(find_contour_points(s.positions, s.normals, {}, 0.f, camera, {.interior = false}), Error);
  EXPECT_THROW(find_contour_points(s.positions, {}, {}, 0.01f, camera, {.interior = true}), Error);
}

}  // namespace
}  // namespace pcsketch::view
