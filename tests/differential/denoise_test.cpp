// Known answers of the noise stage: clean clouds are left alone, noisy spheres come back to their radius and their
// curvature, noisy cubes keep their faces flat up to the edges.

#include "pcsketch/differential/denoise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "pcsketch/differential/curvature.h"
#include "pcsketch/differential/normals.h"
#include "pcsketch/differential/surface.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "support/analytic_shapes.h"

namespace pcsketch::differential {
namespace {

/// The filter itself, whatever the noise: the default trigger (0.25 h) leaves 0.1% of these shapes' diagonals (about
/// 0.14 h at 20k–30k points) raw, as it draws better so (see SparseCloud.SparseNoisySamplesAreDrawnRaw).
const SurfaceOptions kDenoiseAnyNoise{.denoise = {.min_noise_factor = 0.05f}};

/// A sphere of radius 1 and 20k points with Gaussian noise of `fraction` of its bounding-box diagonal.
PointCloud noisy_sphere(float fraction, std::uint32_t seed) {
  const float sigma = fraction * test::diagonal(test::sphere(1.f, {.n = 1000}));
  PointCloud cloud = test::sphere(1.f, {.n = 20000, .seed = seed, .noise_sigma = sigma});
  cloud.normals.clear();
  return cloud;
}

double rms_radius_error(const PointCloud& cloud) {
  double sum = 0;
  for (const Vec3f& p : cloud.positions) sum += std::pow(p.norm() - 1.0, 2);
  return std::sqrt(sum / static_cast<double>(cloud.size()));
}

/// Fraction of the points whose two principal curvatures are within `tolerance` of 1 (the unit sphere's).
double curvature_within(const Surface& s, float tolerance) {
  std::size_t good = 0;
  for (std::size_t i = 0; i < s.curvature.k1.size(); ++i)
    good += std::abs(s.curvature.k1[i] - 1.f) < tolerance && std::abs(s.curvature.k2[i] - 1.f) < tolerance;
  return static_cast<double>(good) / static_cast<double>(s.curvature.k1.size());
}

TEST(Denoise, CleanCloudsAreNotMoved) {
  for (PointCloud cloud : {test::sphere(1.f, {.n = 20000, .seed = 1}), test::cube(1.f, {.n = 20000, .seed = 2}),
                           test::torus(1.f, 0.3f, {.n = 20000, .seed = 3})}) {
    cloud.normals.clear();
    PointCloud moved = cloud;
    const Surface s = analyse_surface(moved, {.reorder = false});
    EXPECT_FALSE(s.denoised) << "noise " << s.input_noise << ", h " << s.spacing;
    EXPECT_LT(s.input_noise, 0.05f * s.spacing);
    EXPECT_EQ(moved.positions, cloud.positions);
  }
}

struct NoisySphere {
  float fraction;             ///< noise σ, fraction of the diagonal
  float curvature_tolerance;  ///< relative, at 90% of the points
  float normal_degrees;       ///< normals within this of the radial direction at 95% of the points
};

class DenoiseSphere : public ::testing::TestWithParam<NoisySphere> {};

TEST_P(DenoiseSphere, ComesBackToItsRadiusAndCurvature) {
  const NoisySphere c = GetParam();
  PointCloud cloud = noisy_sphere(c.fraction, 11);
  const double before = rms_radius_error(cloud);
  const Surface s = analyse_surface(cloud, kDenoiseAnyNoise);
  ASSERT_TRUE(s.denoised);
  EXPECT_NEAR(s.input_noise, before, 0.25 * before);  // the estimate of σ
  EXPECT_LT(rms_radius_error(cloud), 0.35 * before);
  EXPECT_GE(curvature_within(s, c.curvature_tolerance), 0.90)
      << "fit over " << s.curvature.fit_neighbours << " neighbours";
  std::size_t radial = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    radial += cloud.normals[i].dot(cloud.positions[i].normalized()) > std::cos(c.normal_degrees * 3.14159265f / 180.f);
  EXPECT_GE(static_cast<double>(radial), 0.95 * static_cast<double>(cloud.size()));
}

INSTANTIATE_TEST_SUITE_P(TwoNoiseLevels, DenoiseSphere,
                         ::testing::Values(NoisySphere{0.001f, 0.10f, 3.f}, NoisySphere{0.003f, 0.20f, 6.f}));

// The filter and the projection take the neighbours four at a time and the rest one at a time. Each neighbour's
// weight is a function of the pair alone, so a list's order does not matter: its nearest k − 1 reversed (the last one
// sets the reach), another set falls to the single ones, and the points move the same to within rounding.
TEST(Denoise, TheOrderOfANeighbourListDoesNotMatter) {
  for (const std::size_t k : {7u, 14u, 16u}) {
    PointCloud cloud = noisy_sphere(0.001f, 13);
    std::optional<neighbourhood::KdTree> tree;
    neighbourhood::Neighbourhoods lists = neighbourhood::index_neighbourhoods(cloud.positions, tree, {.k = k});
    neighbourhood::Neighbourhoods reversed = lists;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      std::reverse(reversed.indices.begin() + static_cast<std::ptrdiff_t>(i * k),
                   reversed.indices.begin() + static_cast<std::ptrdiff_t>(i * k + k - 1));
      std::reverse(reversed.distances.begin() + static_cast<std::ptrdiff_t>(i * k),
                   reversed.distances.begin() + static_cast<std::ptrdiff_t>(i * k + k - 1));
    }
    const std::vector<Vec3f> normals = estimate_normals(cloud.positions, lists).normals;
    const float spacing = 0.02f;  // about the sphere's at 20k points; any trigger under the noise will do
    const DenoiseOptions options{.min_noise_factor = 0.01f};
    std::vector<Vec3f> a = cloud.positions, b = cloud.positions;
    ASSERT_TRUE(denoise(a, lists, spacing, normals, options).applied) << k << " neighbours";
    ASSERT_TRUE(denoise(b, reversed, spacing, normals, options).applied) << k << " neighbours";
    float largest = 0, moved = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      largest = std::max(largest, (a[i] - b[i]).norm());
      moved = std::max(moved, (a[i] - cloud.positions[i]).norm());
    }
    EXPECT_LT(largest, 1e-4f * moved) << k << " neighbours; the largest move " << moved;
  }
}

TEST(Denoise, NoisyCubeFacesStayFlatUpToTheEdges) {
  const float sigma = 0.001f * 2.f * std::sqrt(3.f);  // 0.1% of the diagonal
  PointCloud cube = test::cube(1.f, {.n = 30000, .seed = 7, .noise_sigma = sigma});
  cube.normals.clear();
  const Surface s = analyse_surface(cube, kDenoiseAnyNoise);
  ASSERT_TRUE(s.denoised);
  // Distance of each point to the nearest face plane, for points 2h to 6h from every edge (the band a smoothing
  // that rounds edges would pull inwards) and for points farther in.
  double near_sum = 0, far_sum = 0;
  std::size_t near_count = 0, far_count = 0;
  for (const Vec3f& p : cube.positions) {
    const Vec3f a = p.cwiseAbs();
    Eigen::Index axis;
    const float out = a.maxCoeff(&axis);
    float edge = 1e9f;  // distance to the nearest edge of that face, in the face
    for (int b = 0; b < 3; ++b)
      if (b != axis) edge = std::min(edge, 1.f - a[b]);
    const double offset = std::pow(out - 1.f, 2);
    if (edge > 2 * s.spacing && edge < 6 * s.spacing) near_sum += offset, ++near_count;
    if (edge >= 6 * s.spacing) far_sum += offset, ++far_count;
  }
  const double near_rms = std::sqrt(near_sum / static_cast<double>(near_count));
  const double far_rms = std::sqrt(far_sum / static_cast<double>(far_count));
  // The noise halves inside the faces and falls by a quarter next to the edges, whose normals the filter keeps apart
  // (a smoothing that rounded the edges would pull those points inwards, by more than σ).
  EXPECT_LT(near_rms, 0.75 * sigma);
  EXPECT_LT(far_rms, 0.5 * sigma);
}

TEST(Denoise, OffLeavesTheNoise) {
  PointCloud cloud = noisy_sphere(0.001f, 12);
  const PointCloud before = cloud;
  const Surface s = analyse_surface(cloud, {.denoise = {.enabled = false}, .reorder = false});
  EXPECT_FALSE(s.denoised);
  EXPECT_EQ(cloud.positions, before.positions);
}

// Noise is the same at every fit size; a coarse shape's misfit grows with it. The share of the residual that stays
// at 40 neighbours tells them apart: near 1 on a noisy sphere and a noisy torus, small on a clean coarse torus whose
// tube is 3 spacings across.
TEST(Denoise, NoiseShareSeparatesNoiseFromMisfit) {
  const auto share = [](PointCloud cloud) {
    cloud.normals.clear();
    const Surface s = analyse_surface(cloud, {.denoise = {.enabled = false}, .reorder = false});
    return noise_share(cloud.positions, cloud.normals, s.neighbourhoods);
  };
  EXPECT_GT(share(noisy_sphere(0.001f, 21)), 0.9f);
  EXPECT_GT(share(test::torus(1.f, 0.3f, {.n = 20000, .seed = 22, .noise_sigma = 0.004f})), 0.9f);
  EXPECT_LT(share(test::torus(1.f, 0.1f, {.n = 600, .seed = 23})), 0.5f);
}

}  // namespace
}  // namespace pcsketch::differential
