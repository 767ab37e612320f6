#include "pcsketch/view/visibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tuple>

#include "pcsketch/core/error.h"
#include "pcsketch/differential/normals.h"
#include "support/analytic_shapes.h"
#include "view/view_test_support.h"

namespace pcsketch::view {
namespace {

using testing::Analysed;

float visible_fraction(const ViewLine& line) {
  float seen = 0;
  for (const std::uint8_t v : line.visible) seen += static_cast<float>(v);
  return seen / static_cast<float>(line.visible.size());
}

/// A straight line of kind Ridge from a to b with a vertex every `step`.
Polyline segment_line(const Vec3f& a, const Vec3f& b, float step) {
  Polyline line;
  line.kind = LineKind::Ridge;
  const int n = std::max(2, static_cast<int>(std::ceil((b - a).norm() / step)) + 1);
  for (int i = 0; i < n; ++i) line.points.push_back(a + (b - a) * (static_cast<float>(i) / static_cast<float>(n - 1)));
  return line;
}

TEST(Visibility, RearSphereContourHiddenWhereTheFrontSphereCoversIt) {
  // Front sphere at the origin, rear sphere 3 units further along the sight (+z), shifted by 1.2 in x: its rim
  // point at angle θ around its centre is covered when (1.2 + cos θ)² + sin² θ < 1, i.e. cos θ < −0.6.
  PointCloud cloud = test::sphere(1.f, {.n = 20000, .seed = 1});
  const PointCloud rear = test::sphere(1.f, {.n = 20000, .seed = 2}, Vec3f(1.2f, 0.f, 3.f));
  cloud.positions.insert(cloud.positions.end(), rear.positions.begin(), rear.positions.end());
  cloud.normals.insert(cloud.normals.end(), rear.normals.begin(), rear.normals.end());
  const Analysed scene(std::move(cloud));
  const ViewResult view = scene.view({.direction = Vec3d(0, 0, 1)});

  int agree = 0, total = 0, hidden = 0, seen = 0;
  for (std::size_t l = 0; l < view.contour_count; ++l) {
    const ViewLine& line = view.lines[l];
    for (std::size_t i = 0; i < line.line.size(); ++i) {
      const Vec3f p = line.line.points[i];
      const Vec2f rim(p.x() - 1.2f, p.y());
      if (p.z() < 2.f || std::abs(rim.norm() - 1.f) > 0.05f) continue;  // not on the rear rim
      const float cos_theta = rim.x() / rim.norm();
      if (std::abs(cos_theta + 0.6f) < 0.05f) continue;  // within a few pixels of the occluder's silhouette
      const bool expect_seen = cos_theta > -0.6f;
      ++total;
      agree += (line.visible[i] != 0) == expect_seen ? 1 : 0;
      (line.visible[i] ? seen : hidden) += 1;
    }
  }
  EXPECT_GT(hidden, 30);
  EXPECT_GT(seen, 100);
  EXPECT_GE(agree, 0.97 * total);
  // The front sphere's outline is seen all round.
  for (std::size_t l = 0; l < view.contour_count; ++l)
    for (std::size_t i = 0; i < view.lines[l].line.size(); ++i)
      if (view.lines[l].line.points[i].z() < 1.5f) {
        EXPECT_EQ(view.lines[l].visible[i], 1);
      }
}

TEST(Visibility, CubeFromACornerHidesTheThreeBackEdges) {
  const Analysed cube(test::cube(1.f, {.n = 30000}));
  // Viewer on the (−1, −1, −1) side looking along +(1, 1, 1): the edges meeting at (1, 1, 1) are behind.
  const Vec3f far(1, 1, 1);
  std::vector<Polyline> edges;
  std::vector<bool> back;
  for (int axis = 0; axis < 3; ++axis)
    for (const float s : {-1.f, 1.f})
      for (const float t : {-1.f, 1.f}) {
        Vec3f a, b;
        a[axis] = -1.f;
        b[axis] = 1.f;
        a[(axis + 1) % 3] = b[(axis + 1) % 3] = s;
        a[(axis + 2) % 3] = b[(axis + 2) % 3] = t;
        edges.push_back(segment_line(a, b, 0.02f));
        back.push_back(a.isApprox(far) || b.isApprox(far));
      }
  const ViewResult view = cube.view({.direction = Vec3d(1, 1, 1)}, edges);
  ASSERT_EQ(view.lines.size(), view.contour_count + 12);
  int hidden_edges = 0;
  for (std::size_t e = 0; e < 12; ++e) {
    const ViewLine& line = view.lines[view.contour_count + e];
    EXPECT_EQ(line.line.kind, LineKind::Ridge);
    if (back[e]) {
      ++hidden_edges;
      EXPECT_LT(visible_fraction(line), 0.1f) << "back edge " << e;
    } else {
      EXPECT_GT(visible_fraction(line), 0.95f) << "front edge " << e;
    }
  }
  EXPECT_EQ(hidden_edges, 3);
}

TEST(Visibility, CubeEdgesTracedInsideTheSolidAreSeenFromTheirSourcePlanes) {
  // A traced ridge runs through the middle of its feature band, which at a convex edge lies inside the solid; with
  // PCA normals (blended across the edge, as a raw scan gets them) the discs near the edge tilt towards the viewer.
  // Each edge of the cube is such a line: every vertex at the centroid of the 8 cloud points nearest to the edge
  // (about 0.5 h below the nearer face), traced from the nearest of them. An edge is seen exactly when one of its
  // faces is front-facing; 30 random views, edges with a face within ~6° of edge-on skipped (ambiguous).
  PointCloud cloud = test::cube(1.f, {.n = 20000});
  differential::Surface surface = testing::exact_surface(cloud);
  const neighbourhood::KdTree tree(cloud.positions);
  const differential::NormalResult pca = differential::estimate_normals(cloud.positions, surface.neighbourhoods);
  for (std::size_t i = 0; i < cloud.size(); ++i)  // signs from the exact normals: orientation is not under test
    cloud.normals[i] = pca.normals[i].dot(cloud.normals[i]) < 0 ? Vec3f(-pca.normals[i]) : pca.normals[i];
  const SurfaceScene scene = build_surface_scene(cloud, surface);
  const float h = surface.spacing;

  std::vector<Polyline> edges;
  std::vector<std::array<Vec3f, 2>> face_normals;
  std::vector<std::uint32_t> near;
  std::vector<float> distances;
  for (int axis = 0; axis < 3; ++axis)
    for (const float s : {-1.f, 1.f})
      for (const float t : {-1.f, 1.f}) {
        Vec3f a, b, n1 = Vec3f::Zero(), n2 = Vec3f::Zero();
        a[axis] = -0.9f;
        b[axis] = 0.9f;
        a[(axis + 1) % 3] = b[(axis + 1) % 3] = n1[(axis + 1) % 3] = s;
        a[(axis + 2) % 3] = b[(axis + 2) % 3] = n2[(axis + 2) % 3] = t;
        Polyline line = segment_line(a, b, h);
        for (Vec3f& p : line.points) {
          tree.knn(p, /*k=*/8, near, distances);
          Vec3f centroid = Vec3f::Zero();
          for (const std::uint32_t j : near) centroid += cloud.positions[j];
          p = centroid / static_cast<float>(near.size());
          line.point_index.push_back(near.front());
        }
        edges.push_back(std::move(line));
        face_normals.push_back({n1, n2});
      }

  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  int seen_visible = 0, seen_total = 0, hidden_hidden = 0, hidden_total = 0;
  for (int v = 0; v < 30; ++v) {
    const Vec3d direction(gauss(rng), gauss(rng), gauss(rng));
    const Camera camera = make_camera(cloud.positions, cloud.origin, {.direction = direction});
    const std::vector<ViewLine> lines = line_visibility(edges, scene, camera, h);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const float c1 = -face_normals[e][0].dot(camera.forward), c2 = -face_normals[e][1].dot(camera.forward);
      if (std::abs(c1) < 0.1f || std::abs(c2) < 0.1f) continue;
      const bool seen = std::max(c1, c2) > 0;
      for (const std::uint8_t flag : lines[e].visible) {
        (seen ? seen_visible : hidden_hidden) += seen ? flag : 1 - flag;
        (seen ? seen_total : hidden_total) += 1;
      }
    }
  }
  ASSERT_GT(seen_total, 10000);
  ASSERT_GT(hidden_total, 3000);
  // Measured 0.985 and 0.998; cast from the vertex itself (lift_to_source_plane = false) 0.959 of the seen ones.
  EXPECT_GE(static_cast<double>(seen_visible) / seen_total, 0.975);
  EXPECT_GE(static_cast<double>(hidden_hidden) / hidden_total, 0.99);
}

TEST(Visibility, NoisySheetSeenAtAGrazingAngleDoesNotHideItself) {
  PointCloud sheet = test::plane(1.f, {.n = 20000, .noise_sigma = 0.003f});
  const Analysed plane(std::move(sheet));
  const std::vector<Polyline> lines{segment_line(Vec3f(-0.8f, 0.f, 0.f), Vec3f(0.8f, 0.f, 0.f), 0.01f),
                                    segment_line(Vec3f(0.f, -0.8f, 0.f), Vec3f(0.f, 0.8f, 0.f), 0.01f)};
  // Sight about 10° above the plane, from its +z side (where its normals point); the noise (a third of h) tilts
  // the discs so the grazing rays cross the neighbours' discs.
  const ViewResult view = plane.view({.direction = Vec3d(0, 1, -0.18)}, lines);
  for (std::size_t l = view.contour_count; l < view.lines.size(); ++l)
    EXPECT_GT(visible_fraction(view.lines[l]), 0.95f);
}

TEST(Visibility, RimOfASparsePartIsSeenPastItsOwnLargeDiscs) {
  // A sphere seen along +z: 15,000 points on its front cap (z < −0.5) and 450 on the rest, so h is set by the cap
  // (≈ 0.01) while the discs at the rim (z = 0) have radii ≈ 0.2. The rim's rays leave tangentially and cross the
  // discs of its sparse neighbours in front, at about half the neighbour's angle from the rim (up to ~0.1): past 3h.
  PointCloud cloud;
  for (const auto& [n, seed, front] : {std::tuple{60000, 1u, true}, std::tuple{600, 2u, false}}) {
    const PointCloud s = test::sphere(1.f, {.n = static_cast<std::size_t>(n), .seed = seed});
    for (std::size_t i = 0; i < s.size(); ++i)
      if ((s.positions[i].z() < -0.5f) == front) {
        cloud.positions.push_back(s.positions[i]);
        cloud.normals.push_back(s.normals[i]);
      }
  }
  const Analysed sphere(std::move(cloud));
  Polyline rim;
  rim.kind = LineKind::Contour;
  rim.closed = true;
  const neighbourhood::KdTree tree(sphere.cloud.positions);
  std::vector<std::uint32_t> nearest;
  std::vector<float> distance;
  for (int i = 0; i < 360; ++i) {
    const float a = static_cast<float>(i) * 3.14159265f / 180.f;
    rim.points.emplace_back(std::cos(a), std::sin(a), 0.f);
    tree.knn(rim.points.back(), 1, nearest, distance);
    rim.point_index.push_back(nearest[0]);
  }
  const std::vector<Polyline> lines{rim};
  const ViewResult local = sphere.view({.direction = Vec3d(0, 0, 1)}, lines);
  EXPECT_GT(visible_fraction(local.lines.back()), 0.95f);  // measured 0.989
  // Offsets in units of h hide most of it (measured 0.39 seen).
  ViewOptions global;
  global.visibility.offset_from_local_spacing = false;
  EXPECT_LT(visible_fraction(sphere.view({.direction = Vec3d(0, 0, 1)}, lines, global).lines.back()), 0.8f);
}

TEST(Visibility, RunsSplitWhereVisibilityChanges) {
  // A line passing behind a sphere: hidden in the middle, split close to the sphere's silhouette (x = ±1).
  const Analysed sphere(test::sphere(1.f, {.n = 20000}));
  const std::vector<Polyline> lines{segment_line(Vec3f(-2.f, 0.f, 2.f), Vec3f(2.f, 0.f, 2.f), 0.1f)};
  const ViewResult view = sphere.view({.direction = Vec3d(0, 0, 1)}, lines);
  const ViewLine& line = view.lines.back();
  ASSERT_EQ(line.runs.size(), 3u);
  EXPECT_TRUE(line.runs[0].visible);
  EXPECT_FALSE(line.runs[1].visible);
  EXPECT_TRUE(line.runs[2].visible);
  // The runs share their split points, which lie where the sphere's silhouette crosses the line (|x| = 1), within
  // the disc radius.
  EXPECT_EQ(line.runs[0].points.back(), line.runs[1].points.front());
  EXPECT_NEAR(line.runs[1].points.front().x(), -1.f, 0.04f);
  EXPECT_NEAR(line.runs[1].points.back().x(), 1.f, 0.04f);
  EXPECT_NEAR(line.runs[1].param.front(), 10.f, 0.5f);
}

TEST(Visibility, SeenLineIsOneVisibleRun) {
  Polyline square;
  square.points = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0)};
  square.closed = true;
  const Camera camera = make_camera(square.points, Vec3d::Zero());
  const ViewLine line = seen_line(square, camera);
  ASSERT_EQ(line.runs.size(), 1u);
  EXPECT_EQ(line.runs[0].points.size(), 5u);  // back to the start: the closing segment is part of the run
  EXPECT_EQ(line.runs[0].param.back(), 4.f);
}

TEST(Visibility, RejectsEvenSmoothingWindow) {
  const PointCloud s = test::sphere(1.f, {.n = 100});
  const SurfaceScene scene(s.positions, s.normals, std::vector<float>(s.size(), 0.1f));
  const Camera camera = make_camera(s.positions, s.origin);
  EXPECT_THROW(line_visibility({}, scene, camera, 0.1f, {.smoothing_window = 2}), Error);
  EXPECT_THROW(line_visibility({}, scene, camera, 0.f), Error);
}

}  // namespace
}  // namespace pcsketch::view
