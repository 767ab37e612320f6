// Depth edges: a surface that ends in front of another, as a scan recorded from one side does at its interior
// contours, has an occluding contour where it ends, though n·v never changes sign on it. The border search (features)
// marks where the surface ends; the view (view/depth_edges) draws the marks beyond which the image lies far behind.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "pcsketch/features/boundary_lines.h"
#include "pcsketch/view/contours.h"
#include "support/analytic_shapes.h"
#include "view/view_test_support.h"

namespace pcsketch::view {
namespace {

using testing::Analysed;

constexpr float kPi = 3.14159265358979f;
const CameraOptions kAlongMinusX{.direction = Vec3d(-1, 0, 0)};
const float kDefault = ContourOptions{}.depth_edge_factor;

/// A cloud analysed for views, with its border (features::find_boundaries).
struct Scene {
  Analysed analysed;
  features::Boundary boundary;
  const std::vector<std::uint8_t>& border = boundary.border;

  explicit Scene(PointCloud cloud)
      : analysed(std::move(cloud)),
        boundary(features::find_boundaries(analysed.cloud.positions, analysed.cloud.normals,
                                           analysed.surface.neighbourhoods, analysed.surface.spacing)) {}

  /// The view along -x, with the boundary lines.
  ViewResult view(float depth_edge_factor) const {
    ViewOptions o;
    o.contours.depth_edge_factor = depth_edge_factor;
    const Camera camera = make_camera(analysed.cloud.positions, analysed.cloud.origin, kAlongMinusX);
    return compute_view(analysed.cloud, analysed.surface, analysed.scene, boundary.lines, camera, o, border);
  }

  /// The contour points of the view along -x.
  ContourPoints contour_points(const ContourOptions& o) const {
    const Camera camera = make_camera(analysed.cloud.positions, analysed.cloud.origin, kAlongMinusX);
    return find_contour_points(analysed.cloud.positions, analysed.cloud.normals, analysed.surface.neighbourhoods,
                               analysed.surface.spacing, camera, o, 0.f, border);
  }

  /// The rim samples of the view along -x.
  std::vector<Vec3f> rim_samples(float depth_edge_factor) const {
    ContourOptions o;
    o.depth_edge_factor = depth_edge_factor;
    return contour_points(o).rim;
  }

  std::size_t edge_points() const {
    return static_cast<std::size_t>(std::count(border.begin(), border.end(), features::Boundary::kEdge));
  }
};

/// The points of `front` with x > min_x, then a 4 × 4 wall facing +x at x = -wall_depth, as dense as a unit sphere of
/// 30,000 points: seen along -x, the wall fills the image around the front surface.
PointCloud in_front_of_wall(const PointCloud& front, float min_x, float wall_depth) {
  PointCloud cloud;
  for (std::size_t i = 0; i < front.size(); ++i)
    if (front.positions[i].x() > min_x) {
      cloud.positions.push_back(front.positions[i]);
      cloud.normals.push_back(front.normals[i]);
    }
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> side(-2.f, 2.f);
  const auto wall_points = static_cast<std::size_t>(16 * 30000 / (4 * kPi));
  for (std::size_t i = 0; i < wall_points; ++i) {
    cloud.positions.emplace_back(-wall_depth, side(rng), side(rng));
    cloud.normals.emplace_back(1.f, 0.f, 0.f);
  }
  return cloud;
}

/// The share of the unit circle around the x axis (the projected rim of a unit sphere seen along -x), in 1° arcs,
/// that seen contour and boundary segments run along within 2 px; and their vertices within 0.9 of the centre (none
/// should).
struct CircleCover {
  float covered = 0;
  std::size_t inside = 0;
};

CircleCover circle_cover(const ViewResult& view) {
  const Vec2f centre = view.camera.project(Vec3f::Zero()).head<2>();
  const float radius = view.camera.scale;
  std::vector<char> arc(360, 0);
  const auto mark = [&](const Vec2f& q) {
    const Vec2f d = q - centre;
    if (std::abs(d.norm() - radius) > 2.f) return;
    const int degree = static_cast<int>(std::floor((std::atan2(d.y(), d.x()) + kPi) * 180.f / kPi));
    arc[static_cast<std::size_t>(std::clamp(degree, 0, 359))] = 1;
  };
  CircleCover cover;
  for (const ViewLine& line : view.lines) {
    if (line.line.kind != LineKind::Contour && line.line.kind != LineKind::Boundary) continue;
    for (std::size_t v = 0; v < line.projected.size(); ++v) {
      if (!line.visible[v]) continue;
      const Vec2f a = line.projected[v].head<2>();
      if ((a - centre).norm() < 0.9f * radius) ++cover.inside;
      if (v + 1 == line.projected.size() || !line.visible[v + 1]) continue;
      const Vec2f b = line.projected[v + 1].head<2>();
      for (float t = 0; t < 1; t += 0.5f / std::max((b - a).norm(), 0.5f)) mark(a + t * (b - a));
    }
  }
  cover.covered = static_cast<float>(std::count(arc.begin(), arc.end(), 1)) / 360.f;
  return cover;
}

// The front half of a sphere, 0.12 (about 12 h) in front of a wall: the border search finds that the surface ends
// there, with the wall in the cone beyond along much of the rim (an edge, not the scan's border). The rim is drawn
// all round (the wall lies more than the default 10 h behind it), and without the depth-edge test almost none of it.
TEST(DepthEdges, AHalfSphereInFrontOfAWallHasItsRimDrawn) {
  const Scene scene(in_front_of_wall(test::sphere(1.f, {.n = 30000}), 0.f, 0.12f));
  EXPECT_GT(scene.edge_points(), 100u);
  const CircleCover with = circle_cover(scene.view(kDefault)), without = circle_cover(scene.view(0.f));
  EXPECT_GT(with.covered, 0.95f);
  EXPECT_EQ(with.inside, 0u);
  EXPECT_LT(without.covered, 0.1f);
}

// On a denoised cloud interior contours shorter than denoised_min_length_factor are dropped as noise squiggles; a
// chain of depth edges is none and keeps min_length_factor. With that minimum above any line, the half sphere's rim
// is still traced (its length is 2π), and the same samples not marked as depth edges give no line.
TEST(DepthEdges, DepthEdgeChainsKeepTheCleanMinimumLengthOnADenoisedCloud) {
  const Scene scene(in_front_of_wall(test::sphere(1.f, {.n = 30000}), 0.f, 0.12f));
  ContourOptions o;
  o.denoised_min_length_factor = 1e6f;
  ContourPoints points = scene.contour_points(o);
  ASSERT_LT(points.depth_edges_begin, points.rim.size());
  const auto interior_length = [&] {
    float length = 0;
    for (const Polyline& line :
         connect_contours(points, scene.analysed.cloud.positions, scene.analysed.surface.spacing, o, /*denoised=*/true)
             .interior)
      length += line.length();
    return length;
  };
  EXPECT_GT(interior_length(), 0.9f * 2 * kPi);
  points.depth_edges_begin = points.rim.size();
  EXPECT_EQ(interior_length(), 0.f);
}

// The same wall 0.05 (about 5 h) behind: the rim is no depth edge (nor a border: the wall fills its cone).
TEST(DepthEdges, ASurfaceCloseBehindMakesNoDepthEdge) {
  const Scene scene(in_front_of_wall(test::sphere(1.f, {.n = 30000}), 0.f, 0.05f));
  EXPECT_LT(circle_cover(scene.view(kDefault)).covered, 0.1f);
}

// A whole sphere in front of the wall: its rim is found by n·v, and the surface ends nowhere. The border search
// leaves a few gaps of the random sampling as edges (their cone fills beyond 2.5 r); those on the steep band by the
// rim, where the sphere's own surface beyond lies over 5 h behind, are drawn over the rim's line: all within 5 h of
// the projected circle. A square facing the viewer ends in front of the wall at its border, which the boundary lines
// draw: no sample.
TEST(DepthEdges, ClosedSurfacesAndFacingBordersMakeNoDepthEdges) {
  const Scene sphere(in_front_of_wall(test::sphere(1.f, {.n = 30000}), -2.f, 1.5f));
  const std::vector<Vec3f> without = sphere.rim_samples(0.f), with = sphere.rim_samples(kDefault);
  EXPECT_GT(without.size(), 300u);
  ASSERT_GE(with.size(), without.size());
  EXPECT_LT(with.size() - without.size(), without.size() / 20);
  const float h = sphere.analysed.surface.spacing;
  for (std::size_t r = without.size(); r < with.size(); ++r) EXPECT_LT(std::abs(with[r].tail<2>().norm() - 1), 5 * h);
  PointCloud square = test::plane(1.f, {.n = 10000});
  for (Vec3f& p : square.positions) p = Vec3f(0.5f, p.x(), p.y());  // the square [-1, 1]² at x = 0.5, facing +x
  for (Vec3f& n : square.normals) n = Vec3f(1.f, 0.f, 0.f);
  const Scene facing(in_front_of_wall(square, -2.f, 0.5f));
  EXPECT_EQ(facing.rim_samples(kDefault).size(), facing.rim_samples(0.f).size());
}

}  // namespace
}  // namespace pcsketch::view
