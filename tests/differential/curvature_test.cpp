// Known-answer tests of normals, orientation and principal curvatures on analytic shapes.

#include "pcsketch/differential/curvature.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "pcsketch/differential/surface.h"
#include "pcsketch/io/read_cloud.h"
#include "support/analytic_shapes.h"

namespace pcsketch::differential {
namespace {

/// Analyses `cloud` with its file normals dropped; the cloud is reordered in place, `truth` (the generator's exact
/// normals) follows through source_index.
struct Analysed {
  PointCloud cloud;
  std::vector<Vec3f> truth;
  Surface surface;
};

Analysed analyse(PointCloud cloud, const SurfaceOptions& options = {}) {
  Analysed a;
  const std::vector<Vec3f> truth = cloud.normals;
  cloud.normals.clear();
  a.surface = analyse_surface(cloud, options);
  a.truth.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) a.truth[i] = truth[cloud.source_index[i]];
  a.cloud = std::move(cloud);
  return a;
}

/// Fraction of the points passing `keep` for which `ok` holds.
template <class Keep, class Ok>
double fraction(std::size_t n, Keep keep, Ok ok) {
  std::size_t kept = 0, good = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep(i)) continue;
    ++kept;
    good += ok(i) ? 1 : 0;
  }
  return kept ? static_cast<double>(good) / static_cast<double>(kept) : 0.0;
}

constexpr auto kAll = [](std::size_t) { return true; };

TEST(Curvature, SphereWithinThreePercent) {
  const float r = 2.f;
  const Analysed a = analyse(test::sphere(r, {.n = 20000, .seed = 7}));
  const Curvature& c = a.surface.curvature;
  const double within = fraction(a.cloud.size(), kAll, [&](std::size_t i) {
    return std::abs(c.k1[i] * r - 1.f) < 0.03f && std::abs(c.k2[i] * r - 1.f) < 0.03f;
  });
  EXPECT_GE(within, 0.95);
  // Normals radial and outward.
  for (std::size_t i = 0; i < a.cloud.size(); ++i) ASSERT_GT(a.cloud.normals[i].dot(a.truth[i]), 0.99f) << i;
}

TEST(Curvature, NoisySphereWithinTenPercent) {
  const float r = 1.f;
  test::SampleSpec spec{.n = 20000, .seed = 11};
  spec.noise_sigma = 0.001f * test::diagonal(test::sphere(r, {.n = 1000}));
  const Analysed a = analyse(test::sphere(r, spec));
  const Curvature& c = a.surface.curvature;
  const double within = fraction(a.cloud.size(), kAll, [&](std::size_t i) {
    return std::abs(c.k1[i] * r - 1.f) < 0.10f && std::abs(c.k2[i] * r - 1.f) < 0.10f;
  });
  EXPECT_GE(within, 0.95) << "fit over " << c.fit_neighbours << " neighbours, noise " << c.noise_sigma;
  EXPECT_GT(c.fit_neighbours, a.surface.neighbourhoods.k);  // the noise was noticed
}

TEST(Curvature, NoiseEstimateOverWideNeighbourhoodsAtAnyScale) {
  // σ̂ from fits over 80 shared neighbours (the inner fit over the first 11 of them) on a torus of tube radius 1 mm
  // and 1 km: the noise found when there is some, and the shape's misfit not taken for noise when there is none.
  for (const float scale : {1e-3f, 1e3f}) {
    for (const float noise : {0.f, 0.01f}) {
      PointCloud cloud = test::torus(4 * scale, scale, {.n = 20000, .seed = 5, .noise_sigma = noise * scale});
      const neighbourhood::KdTree tree(cloud.positions);
      const auto nb = neighbourhood::compute_neighbourhoods(tree, cloud.positions, {.k = 80});
      const float estimate = estimate_noise(cloud.positions, cloud.normals, nb) / scale;
      if (noise == 0)
        EXPECT_LT(estimate, 1e-4f) << "scale " << scale;  // misfit read as noise gave 7.6e-4
      else
        EXPECT_NEAR(estimate, noise, 0.1f * noise) << "scale " << scale;
    }
  }
}

TEST(Curvature, CylinderAwayFromRims) {
  const float r = 1.f, height = 4.f;
  const Analysed a = analyse(test::cylinder(r, height, {.n = 20000, .seed = 3}));
  const Curvature& c = a.surface.curvature;
  const auto inside = [&](std::size_t i) { return std::abs(a.cloud.positions[i].z()) < height / 2 - 0.3f; };
  const double within = fraction(a.cloud.size(), inside, [&](std::size_t i) {
    return std::abs(c.k1[i] * r - 1.f) < 0.03f && std::abs(c.k2[i] * r) < 0.03f &&
           std::abs(c.dir2[i].z()) > 0.99f;  // the straight direction is the axis
  });
  EXPECT_GE(within, 0.95);
  for (std::size_t i = 0; i < a.cloud.size(); ++i) ASSERT_GT(a.cloud.normals[i].dot(a.truth[i]), 0.f) << i;
}

TEST(Curvature, PlaneIsFlat) {
  const Analysed a = analyse(test::plane(1.f, {.n = 5000, .seed = 5}));
  const Curvature& c = a.surface.curvature;
  const float side = a.cloud.normals[0].z() > 0 ? 1.f : -1.f;
  for (std::size_t i = 0; i < a.cloud.size(); ++i) {
    ASSERT_LT(std::abs(c.k1[i]), 1e-3f) << i;
    ASSERT_LT(std::abs(c.k2[i]), 1e-3f) << i;
    ASSERT_GT(side * a.cloud.normals[i].z(), 0.9999f) << i;  // one consistent side
  }
}

TEST(Curvature, SaddleAtTheOrigin) {
  const Analysed a = analyse(test::saddle(0.5f, {.n = 20000, .seed = 9}));
  std::size_t origin = 0;
  for (std::size_t i = 0; i < a.cloud.size(); ++i)
    if (a.cloud.positions[i].norm() < a.cloud.positions[origin].norm()) origin = i;
  ASSERT_LT(a.cloud.positions[origin].norm(), 0.02f);
  const Curvature& c = a.surface.curvature;
  EXPECT_NEAR(c.k1[origin], 2.f, 0.1f);
  EXPECT_NEAR(c.k2[origin], -2.f, 0.1f);
  // z = x² − y² bends towards +z along x and away from it along y. Convex (away from the normal) is positive, so
  // with the normal on the +z side k1 = +2 runs along y; with it on the −z side, along x.
  const Vec3f expected_dir1 = a.cloud.normals[origin].z() > 0 ? Vec3f::UnitY() : Vec3f::UnitX();
  EXPECT_GT(std::abs(c.dir1[origin].dot(expected_dir1)), 0.99f);
  EXPECT_NEAR(c.dir2[origin].dot(a.cloud.normals[origin].cross(c.dir1[origin])), 1.f, 1e-5f);
  EXPECT_NEAR(c.gaussian(origin), -4.f, 0.4f);
  EXPECT_NEAR(c.mean(origin), 0.f, 0.1f);
}

TEST(Curvature, TorusNormalsAllOutward) {
  const Analysed a = analyse(test::torus(1.f, 0.3f, {.n = 20000, .seed = 13}));
  for (std::size_t i = 0; i < a.cloud.size(); ++i) ASSERT_GT(a.cloud.normals[i].dot(a.truth[i]), 0.f) << i;
  EXPECT_EQ(a.surface.components, 1u);
}

TEST(Curvature, TorusOutwardByFarthestPointRuleToo) {
  SurfaceOptions options;
  options.orientation.outward = OutwardRule::FarthestPoint;
  const Analysed a = analyse(test::torus(1.f, 0.3f, {.n = 5000, .seed = 17}), options);
  for (std::size_t i = 0; i < a.cloud.size(); ++i) ASSERT_GT(a.cloud.normals[i].dot(a.truth[i]), 0.f) << i;
}

TEST(Curvature, TorusOutwardByParallelCriterionToo) {
  SurfaceOptions options;
  options.orientation.criterion = OrientCriterion::Parallel;
  const Analysed a = analyse(test::torus(1.f, 0.3f, {.n = 5000, .seed = 19}), options);
  for (std::size_t i = 0; i < a.cloud.size(); ++i) ASSERT_GT(a.cloud.normals[i].dot(a.truth[i]), 0.f) << i;
}

// Sharp edges: the PCA normals of points on an edge lie between the two faces' normals, and across the edge the two
// faces' normals are perpendicular, which the reflection criterion crosses as surely as a flat face.
TEST(Curvature, CubeNormalsAllOutwardAcrossSharpEdges) {
  const Analysed a = analyse(test::cube(1.f, {.n = 30000, .seed = 23}));
  for (std::size_t i = 0; i < a.cloud.size(); ++i) ASSERT_GT(a.cloud.normals[i].dot(a.truth[i]), 0.f) << i;
}

// The fandisk's own vertices: dense strips along its sharp edges, large triangles between them. Ground truth: the
// mesh's area-weighted vertex normals. Hoppe's |n_i·n_j| criterion leaves about a third of them inward here.
TEST(Curvature, FandiskVertexNormalsAgreeWithTheMesh) {
  const std::string path = std::string(PCSKETCH_FIXTURES) + "/fandisk.off";
  const Mesh mesh = io::read_mesh(path);
  std::vector<Vec3f> vertex_normals(mesh.vertices.size(), Vec3f::Zero());
  for (const auto& f : mesh.faces) {
    const Vec3f n = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    for (std::uint32_t v : f) vertex_normals[v] += n;
  }
  PointCloud cloud = io::read_point_cloud(path).cloud;
  ASSERT_EQ(cloud.size(), mesh.vertices.size());
  analyse_surface(cloud);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    ASSERT_GT(cloud.normals[i].dot(vertex_normals[cloud.source_index[i]]), 0.f) << "vertex " << cloud.source_index[i];
}

// Noisy clouds fit once per group of nearby points, except where a crease lies in the support: there each point is
// fitted on its own exact k nearest (docs/geometry.md, "Group fits").
TEST(Curvature, GroupFitsOnSmoothPartsAndPointFitsAtCreases) {
  test::SampleSpec spec{.n = 20000, .seed = 11};
  spec.noise_sigma = 0.001f * test::diagonal(test::sphere(1.f, {.n = 1000}));
  const Analysed sphere = analyse(test::sphere(1.f, spec));
  ASSERT_GT(sphere.surface.curvature.fit_neighbours, sphere.surface.neighbourhoods.k);
  EXPECT_LT(sphere.surface.curvature.point_fits, sphere.cloud.size() / 10);  // smooth: groups share a fit

  const float a = 1.f;
  const Analysed cube = analyse(test::cube(a, {.n = 30000, .seed = 7, .noise_sigma = 0.001f * 2.f * std::sqrt(3.f)}));
  const Curvature& c = cube.surface.curvature;
  ASSERT_GT(c.fit_neighbours, cube.surface.neighbourhoods.k);
  EXPECT_GT(c.point_fits, 0u);
  // The fit radius holding fit_neighbours points on a face of density n / (24 a²); points far from every edge lie
  // on one plane, where the shared fit leaves only the noise.
  const float radius = std::sqrt(static_cast<float>(c.fit_neighbours) * 24.f * a * a / (3.14159265f * 30000.f));
  std::size_t far = 0, far_shared = 0, near_edge_total = 0;
  for (std::size_t i = 0; i < cube.cloud.size(); ++i) {
    const Vec3f p = cube.cloud.positions[i].cwiseAbs();
    // Distance to the nearest edge: the second largest coordinate's gap to the face (a point on a face has one
    // coordinate near a; an edge is where two are).
    std::array<float, 3> q{p.x(), p.y(), p.z()};
    std::sort(q.begin(), q.end());
    const float to_edge = a - q[1];
    if (to_edge > 2.f * radius) {
      ++far;
      far_shared += std::abs(c.k1[i]) < 0.2f && std::abs(c.k2[i]) < 0.2f;
    } else {
      ++near_edge_total;
    }
  }
  ASSERT_GT(far, 1000u);
  EXPECT_GE(static_cast<double>(far_shared), 0.95 * static_cast<double>(far));  // flat faces read as flat
  EXPECT_LE(c.point_fits, near_edge_total);  // fitted alone only near the creases
}

TEST(Curvature, ExplicitFitSizeIsUsed) {
  PointCloud cloud = test::sphere(1.f, {.n = 3000, .seed = 2});
  const neighbourhood::KdTree tree(cloud.positions);
  const auto nb = neighbourhood::compute_neighbourhoods(tree, cloud.positions, {.k = 12});
  const Curvature small = estimate_curvature(cloud.positions, cloud.normals, nb, {.k = 8});
  const Curvature large = estimate_curvature(cloud.positions, cloud.normals, nb, tree, {.k = 40});
  EXPECT_EQ(small.fit_neighbours, 8u);
  EXPECT_EQ(large.fit_neighbours, 40u);
  for (std::size_t i = 0; i < cloud.size(); ++i) ASSERT_NEAR(large.k1[i], 1.f, 0.05f) << i;
}

}  // namespace
}  // namespace pcsketch::differential
