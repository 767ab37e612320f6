#include "pcsketch/view/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "pcsketch/core/error.h"
#include "support/analytic_shapes.h"

namespace pcsketch::view {
namespace {

TEST(Camera, OrthographicFramesSphereWithMargin) {
  const PointCloud s = test::sphere(2.f, {.n = 20000});
  const Camera cam = make_camera(s.positions, s.origin, {.width = 1000, .height = 1000, .margin = 0.1});
  float umin = 1e9f, umax = -1e9f;
  for (const Vec3f& p : s.positions) {
    const Vec3f q = cam.project(p);
    umin = std::min(umin, q.x());
    umax = std::max(umax, q.x());
  }
  EXPECT_NEAR(umin, 100.f, 0.5f);
  EXPECT_NEAR(umax, 900.f, 0.5f);
  EXPECT_NEAR(cam.scale, 800.f / 4.f, 1.f);
}

TEST(Camera, DefaultLooksAlongPlusZAndIsRightHanded) {
  const std::vector<Vec3f> pts{Vec3f(-1, -1, -1), Vec3f(1, 1, 1)};
  const Camera cam = make_camera(pts, Vec3d::Zero());
  EXPECT_TRUE(cam.forward.isApprox(Vec3f(0, 0, 1)));
  EXPECT_TRUE(cam.right.isApprox(cam.forward.cross(cam.up)));
  // +y is up in the image: smaller v.
  EXPECT_LT(cam.project(Vec3f(0, 1, 0)).y(), cam.project(Vec3f(0, -1, 0)).y());
  // Farther along +z is deeper.
  EXPECT_LT(cam.project(Vec3f(0, 0, -1)).z(), cam.project(Vec3f(0, 0, 1)).z());
}

TEST(Camera, AzimuthElevationMatchesDirection) {
  const std::vector<Vec3f> pts{Vec3f(-1, -1, -1), Vec3f(1, 1, 1)};
  const Camera top = make_camera(pts, Vec3d::Zero(), {.elevation_deg = 90.0});
  EXPECT_TRUE(top.forward.isApprox(Vec3f(0, -1, 0), 1e-5f));
  const Camera side = make_camera(pts, Vec3d::Zero(), {.azimuth_deg = 90.0});
  EXPECT_TRUE(side.forward.isApprox(Vec3f(-1, 0, 0), 1e-5f));
}

TEST(Camera, NamedViewsRelativeToUpYUp) {
  const std::vector<Vec3f> pts{Vec3f(-1, -1, -1), Vec3f(1, 1, 1)};
  auto forward = [&](NamedView v) { return make_camera(pts, Vec3d::Zero(), {.named = v}).forward; };
  EXPECT_TRUE(forward(NamedView::Front).isApprox(Vec3f(0, 0, 1), 1e-6f));  // the paper's +z view
  EXPECT_TRUE(forward(NamedView::Back).isApprox(Vec3f(0, 0, -1), 1e-6f));
  EXPECT_TRUE(forward(NamedView::Left).isApprox(Vec3f(-1, 0, 0), 1e-6f));
  EXPECT_TRUE(forward(NamedView::Right).isApprox(Vec3f(1, 0, 0), 1e-6f));
  EXPECT_TRUE(forward(NamedView::Top).isApprox(Vec3f(0, -1, 0), 1e-6f));
  EXPECT_TRUE(forward(NamedView::Bottom).isApprox(Vec3f(0, 1, 0), 1e-6f));
  EXPECT_TRUE(forward(NamedView::Iso).isApprox(Vec3f(1, -1, 1).normalized(), 1e-6f));
  // The right view is seen from the front view's right-hand side, looking back against the front's image right;
  // the front (−z here) is on the image's left.
  const Camera front = make_camera(pts, Vec3d::Zero(), {.named = NamedView::Front});
  const Camera right = make_camera(pts, Vec3d::Zero(), {.named = NamedView::Right});
  EXPECT_LT(front.right.dot(right.forward), -0.999f);
  EXPECT_LT(right.project(Vec3f(0, 0, -1)).x(), right.project(Vec3f(0, 0, 1)).x());
  // Top (third-angle plan): the front's far side is up in the image; bottom: its near side.
  const Camera top = make_camera(pts, Vec3d::Zero(), {.named = NamedView::Top});
  EXPECT_TRUE(top.up.isApprox(Vec3f(0, 0, 1), 1e-6f));
  EXPECT_TRUE(make_camera(pts, Vec3d::Zero(), {.named = NamedView::Bottom}).up.isApprox(Vec3f(0, 0, -1), 1e-6f));
  // Iso: every world axis foreshortened alike (the cube's three visible faces are equal).
  const Camera iso = make_camera(pts, Vec3d::Zero(), {.named = NamedView::Iso});
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(std::abs(iso.forward[axis]), 1.f / std::sqrt(3.f), 1e-6f);
  EXPECT_GT(iso.up.y(), 0.f);
}

TEST(Camera, NamedViewsRelativeToUpZUp) {
  const std::vector<Vec3f> pts{Vec3f(-1, -1, -1), Vec3f(1, 1, 1)};
  const Vec3d z_up(0, 0, 1);
  const Camera front = make_camera(pts, Vec3d::Zero(), {.named = NamedView::Front, .up = z_up});
  EXPECT_TRUE(front.forward.isApprox(Vec3f(1, 0, 0), 1e-6f));
  EXPECT_TRUE(front.up.isApprox(Vec3f(0, 0, 1), 1e-6f));
  const Camera top = make_camera(pts, Vec3d::Zero(), {.named = NamedView::Top, .up = z_up});
  EXPECT_TRUE(top.forward.isApprox(Vec3f(0, 0, -1), 1e-6f));
  EXPECT_TRUE(top.up.isApprox(Vec3f(1, 0, 0), 1e-6f));
  // Named views equal their azimuth/elevation: right is azimuth −90.
  const Camera right = make_camera(pts, Vec3d::Zero(), {.named = NamedView::Right, .up = z_up});
  const Camera az = make_camera(pts, Vec3d::Zero(), {.up = z_up, .azimuth_deg = -90.0, .elevation_deg = 0.0});
  EXPECT_TRUE(right.forward.isApprox(az.forward, 1e-6f));
  // The three-quarter view looks 15 degrees down, never along up.
  const Camera three_quarter = make_camera(pts, Vec3d::Zero(),
                                           {.up = z_up,
                                            .azimuth_deg = kThreeQuarterAzimuthDeg,
                                            .elevation_deg = kThreeQuarterElevationDeg});
  EXPECT_NEAR(three_quarter.forward.z(), -std::sin(15.f * 3.14159265f / 180.f), 1e-5f);
}

TEST(Camera, NamesRoundTrip) {
  for (const NamedView v : {NamedView::Front, NamedView::Back, NamedView::Left, NamedView::Right, NamedView::Top,
                            NamedView::Bottom, NamedView::Iso})
    EXPECT_EQ(parse_named_view(to_string(v)), v);
  EXPECT_FALSE(parse_named_view("sideways"));
  EXPECT_FALSE(parse_named_view(""));
}

TEST(Camera, LookingStraightDownKeepsTheImageUpright) {
  const std::vector<Vec3f> pts{Vec3f(-1, -1, -1), Vec3f(1, 1, 1)};
  // Elevation 90 at azimuth 30: the image's up is the horizontal direction the viewer faced.
  const Camera cam = make_camera(pts, Vec3d::Zero(), {.azimuth_deg = 30.0, .elevation_deg = 90.0});
  EXPECT_TRUE(cam.forward.isApprox(Vec3f(0, -1, 0), 1e-6f));
  const Camera level = make_camera(pts, Vec3d::Zero(), {.azimuth_deg = 30.0, .elevation_deg = 0.0});
  EXPECT_TRUE(cam.up.isApprox(level.forward, 1e-6f));
}

TEST(Camera, PerspectiveNearerIsLarger) {
  const std::vector<Vec3f> pts{Vec3f(-1, -1, -1), Vec3f(1, 1, 1)};
  const Camera cam = make_camera(pts, Vec3d::Zero(), {.projection = Projection::Perspective});
  const float near_width = cam.project(Vec3f(1, 0, -1)).x() - cam.project(Vec3f(-1, 0, -1)).x();
  const float far_width = cam.project(Vec3f(1, 0, 1)).x() - cam.project(Vec3f(-1, 0, 1)).x();
  EXPECT_GT(std::abs(near_width), std::abs(far_width));
  EXPECT_TRUE(cam.ray_direction(Vec3f(0, 0, 0)).isApprox(Vec3f(0, 0, 1), 1e-5f));
}

TEST(Camera, RejectsBadInput) {
  const std::vector<Vec3f> pts{Vec3f::Zero()};
  EXPECT_THROW(make_camera(pts, Vec3d::Zero(), {.direction = Vec3d::Zero()}), Error);
  EXPECT_THROW(make_camera(pts, Vec3d::Zero(), {.width = 0}), Error);
  // A single point and an up hint parallel to the view still give a valid camera.
  const Camera cam = make_camera(pts, Vec3d::Zero(), {.direction = Vec3d(0, 1, 0)});
  EXPECT_NEAR(cam.up.dot(cam.forward), 0.f, 1e-6f);
  EXPECT_TRUE(std::isfinite(cam.scale));
  EXPECT_EQ(cam.to_json()["projection"], "orthographic");
}

}  // namespace
}  // namespace pcsketch::view
