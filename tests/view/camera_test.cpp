#include "pcsketch/view/camera.h"

#include <gtest/gtest.h>

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
