// Known answers for the mesh ground truth the view tests and benches score against (tests/support): a cube's sharp
// edges and which of them a camera sees.

#include "support/mesh_ground_truth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "support/analytic_shapes.h"

namespace pcsketch::test {
namespace {

/// The cube [-1, 1]³ as 12 triangles with outward normals; vertex i has coordinate axis k at +1 when bit k is set.
Mesh cube_mesh() { return box(Vec3f::Ones()); }

float distance_to_segment(const Vec2f& p, const Vec2f& a, const Vec2f& b) {
  const Vec2f ab = b - a;
  const float t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.f, 1.f);
  return (p - (a + t * ab)).norm();
}

struct ImageEdge {
  Vec2f a, b;
};

float distance_to_edges(const Vec2f& p, const std::vector<ImageEdge>& edges) {
  float best = std::numeric_limits<float>::max();
  for (const ImageEdge& e : edges) best = std::min(best, distance_to_segment(p, e.a, e.b));
  return best;
}

bool any_within(const std::vector<Vec2f>& samples, const Vec2f& p, float r) {
  return std::any_of(samples.begin(), samples.end(), [&](const Vec2f& s) { return (s - p).norm() <= r; });
}

TEST(MeshGroundTruth, CubeSharpEdgesAreTwelveConvexOnes) {
  const SharpEdges sharp = sharp_edges(cube_mesh(), 40.f);
  EXPECT_EQ(sharp.convex.size(), 12u);
  EXPECT_TRUE(sharp.concave.empty());
  // The face diagonals are flat (0°); the cube edges (90°) are not sharp above 95°.
  const SharpEdges none = sharp_edges(cube_mesh(), 95.f);
  EXPECT_TRUE(none.convex.empty() && none.concave.empty());
}

TEST(MeshGroundTruth, CubeFromAGenericDirectionShowsNineEdges) {
  const Mesh mesh = cube_mesh();
  const Vec3d direction(-0.8, -0.6, -1.0);
  const view::Camera camera = view::make_camera(mesh.vertices, mesh.origin, {.direction = direction});
  const MeshContourOptions options;
  const MeshSharpEdges truth = mesh_sharp_edges(mesh, camera, 40.f, options);
  ASSERT_EQ(truth.edges.convex.size(), 12u);
  EXPECT_TRUE(truth.edges.concave.empty());
  EXPECT_TRUE(truth.concave.visible.empty() && truth.concave.hidden.empty());

  // The far corner (its coordinates have the signs of the direction of sight) hides its 3 edges; the other 9 show.
  const Vec3f far(direction.x() > 0 ? 1.f : -1.f, direction.y() > 0 ? 1.f : -1.f, direction.z() > 0 ? 1.f : -1.f);
  std::vector<ImageEdge> shown, hidden;
  std::vector<Vec2f> outline_ends;  // where the hidden edges leave the outline
  for (const auto& [a, b] : truth.edges.convex) {
    const ImageEdge e{camera.project(a).head<2>(), camera.project(b).head<2>()};
    const bool from_far = a == far || b == far;
    (from_far ? hidden : shown).push_back(e);
    if (from_far) outline_ends.push_back(camera.project(a == far ? b : a).head<2>());
  }
  ASSERT_EQ(shown.size(), 9u);
  ASSERT_EQ(hidden.size(), 3u);

  // Visible samples lie on the 9 edges, but for the fuzz of the depth window where a hidden edge meets the outline:
  // a window pixel's centre is up to (depth_window + ½)·√2 px from the sample (2 px measured here).
  const float fuzz_px =
      std::sqrt(2.f) * (static_cast<float>(options.depth_window) + 0.5f) + options.sample_step_px;
  std::size_t fuzzy = 0;
  for (const Vec2f& p : truth.convex.visible) {
    if (distance_to_edges(p, shown) <= 0.01f) continue;
    ++fuzzy;
    EXPECT_TRUE(any_within(outline_ends, p, fuzz_px)) << "visible sample off the 9 edges at " << p.transpose();
  }
  EXPECT_LE(fuzzy, 3u * static_cast<std::size_t>(std::ceil(fuzz_px / options.sample_step_px) + 1));
  // Hidden samples lie on the 3 hidden edges.
  for (const Vec2f& p : truth.convex.hidden)
    EXPECT_LE(distance_to_edges(p, hidden), 0.01f) << "hidden sample off the 3 hidden edges at " << p.transpose();

  // Every point of the 9 edges has a visible sample; the 3 hidden edges, away from the outline and from where they
  // cross a shown edge in the image, have hidden samples and no visible one.
  for (const ImageEdge& e : shown)
    for (const float t : {0.f, 0.25f, 0.5f, 0.75f, 1.f})
      EXPECT_TRUE(any_within(truth.convex.visible, e.a + t * (e.b - e.a), options.sample_step_px));
  for (const ImageEdge& e : hidden)
    for (float t = 0.f; t <= 1.f; t += 0.05f) {
      const Vec2f p = e.a + t * (e.b - e.a);
      if (any_within(outline_ends, p, 2.f * fuzz_px) || distance_to_edges(p, shown) <= 2.f * fuzz_px) continue;
      EXPECT_TRUE(any_within(truth.convex.hidden, p, options.sample_step_px)) << "at " << p.transpose();
      EXPECT_FALSE(any_within(truth.convex.visible, p, 1.f)) << "at " << p.transpose();
    }
}

}  // namespace
}  // namespace pcsketch::test
