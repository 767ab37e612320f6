#include "pcsketch/view/view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"
#include "support/analytic_shapes.h"
#include "support/mesh_ground_truth.h"
#include "view/view_test_support.h"

namespace pcsketch::view {
namespace {

using testing::Analysed;

/// A torus around the z axis as a triangle grid (nu around the axis, nv around the tube), for ground truth.
Mesh torus_mesh(float R, float r, int nu, int nv) {
  Mesh mesh;
  const float tau = 2.f * std::numbers::pi_v<float>;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const float u = tau * static_cast<float>(i) / static_cast<float>(nu);
      const float v = tau * static_cast<float>(j) / static_cast<float>(nv);
      mesh.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                                 r * std::sin(v));
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % nu) * nv + j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh;
}

/// Precision/recall of the visible contour runs of `view` against the mesh's visible occluding contours.
test::LineMatch score_contours(const ViewResult& view, const Mesh& mesh) {
  const test::MeshContours truth = test::mesh_contours(mesh, view.camera);
  return test::match_lines(test::sample_view_lines(view.lines, LineKind::Contour, true), truth.visible, 3.f);
}

TEST(View, TorusFromTheSideHasVisibleInteriorContours) {
  const float R = 1.f, r = 0.35f;
  const Analysed torus(test::torus(R, r, {.n = 30000}));
  // About 8.5° off the equatorial plane: the hole is closed in the image, its rims are inside the outline.
  const ViewResult view = torus.view({.direction = Vec3d(0, 1, 0.15)});
  ASSERT_GT(view.contour_count, 1u);
  EXPECT_TRUE(view.lines[0].line.closed);  // the outline
  float interior_visible_px = 0;
  for (std::size_t l = 1; l < view.contour_count; ++l)
    for (const LineRun& run : view.lines[l].runs)
      if (run.visible)
        for (std::size_t i = 1; i < run.projected.size(); ++i)
          interior_visible_px += (run.projected[i] - run.projected[i - 1]).head<2>().norm();
  EXPECT_GT(interior_visible_px, 300.f);
  const test::LineMatch match = score_contours(view, torus_mesh(R, r, 400, 200));
  EXPECT_GE(match.precision, 0.9);
  EXPECT_GE(match.recall, 0.85);
}

/// The camel of the paper (tests/fixtures/meshes/camel.off, a copy of CGAL's demo data), sampled with its face
/// normals, against its own occluding contours.
class CamelViews : public ::testing::TestWithParam<Vec3d> {
 protected:
  static void SetUpTestSuite() {
    mesh_ = new Mesh(io::read_mesh(PCSKETCH_FIXTURES "/meshes/camel.off"));
    camel_ = new Analysed(io::sample_mesh(*mesh_, {.n = 30000, .seed = 7, .keep_normals = true}));
  }
  static void TearDownTestSuite() {
    delete camel_;
    delete mesh_;
  }
  static inline Mesh* mesh_ = nullptr;
  static inline Analysed* camel_ = nullptr;
};

TEST_P(CamelViews, ContoursMatchTheMeshWithin3Px) {
  const ViewResult view = camel_->view({.direction = GetParam(), .width = 1024, .height = 1024});
  const test::LineMatch match = score_contours(view, *mesh_);
  EXPECT_GE(match.precision, 0.85);
  EXPECT_GE(match.recall, 0.85);
}

INSTANTIATE_TEST_SUITE_P(ThreeViews, CamelViews,
                         ::testing::Values(Vec3d(0, 0, 1), Vec3d(1, 0, 0), Vec3d(-1, 0.3, -0.5)));

TEST(View, SecondViewReusesTheSceneAndDiffers) {
  const Analysed torus(test::torus(1.f, 0.35f, {.n = 10000}));
  const ViewResult top = torus.view({.direction = Vec3d(0, 0, 1)});
  const ViewResult side = torus.view({.direction = Vec3d(0, 1, 0.15)});
  EXPECT_EQ(top.contour_count, 2u);
  EXPECT_GT(side.contour_count, 1u);
  EXPECT_FALSE(top.camera.forward.isApprox(side.camera.forward));
  EXPECT_GE(top.timings.contour_points, 0.0);
  EXPECT_GE(side.timings.visibility, 0.0);
}

TEST(View, RejectsCloudWithoutNormals) {
  PointCloud cloud = test::sphere(1.f, {.n = 500});
  const differential::Surface surface = testing::exact_surface(cloud);
  cloud.normals.clear();
  EXPECT_THROW(build_surface_scene(cloud, surface), Error);
}

}  // namespace
}  // namespace pcsketch::view
