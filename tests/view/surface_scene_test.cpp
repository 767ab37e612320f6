#include "pcsketch/view/surface_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pcsketch/core/error.h"
#include "support/analytic_shapes.h"

namespace pcsketch::view {
namespace {

/// A unit sphere of discs whose radius (0.05) overlaps the ~0.025 spacing of 20k points.
SurfaceScene unit_sphere_scene(PointCloud& s) {
  s = test::sphere(1.f, {.n = 20000});
  return SurfaceScene(s.positions, s.normals, std::vector<float>(s.size(), 0.05f));
}

TEST(SurfaceScene, RayHitsSphereFrontAtItsDistance) {
  PointCloud s;
  const SurfaceScene scene = unit_sphere_scene(s);
  const auto hit = scene.intersect(Vec3f(0, 0, -5), Vec3f(0, 0, 1), 0.f, 100.f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 4.f, 0.01f);
  ASSERT_LT(hit->point, s.size());
  EXPECT_LT((s.positions[hit->point] - Vec3f(0, 0, -1)).norm(), 0.06f);
}

TEST(SurfaceScene, OccludedRespectsRayInterval) {
  PointCloud s;
  const SurfaceScene scene = unit_sphere_scene(s);
  EXPECT_FALSE(scene.occluded(Vec3f(0, 0, -5), Vec3f(0, 0, 1), 0.f, 3.9f));
  EXPECT_TRUE(scene.occluded(Vec3f(0, 0, -5), Vec3f(0, 0, 1), 0.f, 100.f));
  // A ray passing beside the sphere hits nothing.
  EXPECT_FALSE(scene.occluded(Vec3f(1.2f, 0, -5), Vec3f(0, 0, 1), 0.f, 100.f));
  EXPECT_FALSE(scene.intersect(Vec3f(1.2f, 0, -5), Vec3f(0, 0, 1), 0.f, 100.f).has_value());
}

TEST(SurfaceScene, SelfHitAvoidedByNearOffset) {
  PointCloud s;
  const SurfaceScene scene = unit_sphere_scene(s);
  // From a front point toward the viewer (−z): with an offset, nothing; with t_near = 0, its own disc.
  std::size_t front = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.positions[i].z() < s.positions[front].z()) front = i;
  EXPECT_FALSE(scene.occluded(s.positions[front], Vec3f(0, 0, -1), 0.1f, 100.f));
  EXPECT_TRUE(scene.occluded(s.positions[front], Vec3f(0, 0, -1), 0.f, 100.f));
  // From a back point toward the viewer: the front of the sphere is in the way, at about 2 units.
  std::size_t back = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.positions[i].z() > s.positions[back].z()) back = i;
  const auto hit = scene.intersect(s.positions[back], Vec3f(0, 0, -1), 0.1f, 100.f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 2.f, 0.01f);
}

TEST(SurfaceScene, FarFromOriginKeepsPrecision) {
  PointCloud s = test::sphere(1.f, {.n = 20000}, Vec3f(5000.f, 0.f, 0.f));
  const SurfaceScene scene(s.positions, s.normals, std::vector<float>(s.size(), 0.05f));
  const auto hit = scene.intersect(Vec3f(5000.f, 0, -5), Vec3f(0, 0, 1), 0.f, 100.f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, 4.f, 0.01f);
}

TEST(SurfaceScene, RejectsMismatchedSizes) {
  const std::vector<Vec3f> p(3, Vec3f::Zero());
  EXPECT_THROW(SurfaceScene(p, std::vector<Vec3f>(2, Vec3f::UnitZ()), std::vector<float>(3, 1.f)), Error);
}

TEST(SurfaceScene, LocalSpacingIsKthNeighbourDistanceClamped) {
  neighbourhood::Neighbourhoods nb;
  nb.k = 3;
  nb.indices = {1, 2, 3, 0, 2, 3};
  nb.distances = {0.1f, 0.2f, 0.4f, 0.5f, 0.6f, 0.7f};
  EXPECT_EQ(local_spacing(nb, 2), (std::vector<float>{0.2f, 0.6f}));
  EXPECT_EQ(local_spacing(nb, /*kth=*/10), (std::vector<float>{0.4f, 0.7f}));
}

TEST(SurfaceScene, DiscsReadBackAsGiven) {
  // Positions back in the caller's coordinates (the scene is recentred inside), normals unit, radius factor applied;
  // a point without a normal keeps its index with radius 0.
  const std::vector<Vec3f> p{Vec3f(5000.f, 1.f, 2.f), Vec3f(5001.f, -1.f, 0.5f), Vec3f(4999.f, 0.f, 0.f)};
  const std::vector<Vec3f> n{Vec3f(0.f, 0.f, 2.f), Vec3f(3.f, 4.f, 0.f), Vec3f::Zero()};
  const SurfaceScene scene(p, n, {0.1f, 0.2f, 0.3f}, {.disc_radius_factor = 1.5f});
  ASSERT_EQ(scene.size(), 3u);
  EXPECT_LT((scene.disc(0).centre - p[0]).norm(), 1e-3f);
  EXPECT_LT((scene.disc(1).normal - Vec3f(0.6f, 0.8f, 0.f)).norm(), 1e-6f);
  EXPECT_FLOAT_EQ(scene.disc(1).radius, 0.3f);
  EXPECT_EQ(scene.disc(2).radius, 0.f);
  EXPECT_THROW(scene.disc(3), Error);
}

TEST(SurfaceScene, EmptySceneHitsNothing) {
  const SurfaceScene scene({}, {}, {});
  EXPECT_FALSE(scene.occluded(Vec3f::Zero(), Vec3f::UnitZ(), 0.f, 1e9f));
}

}  // namespace
}  // namespace pcsketch::view
