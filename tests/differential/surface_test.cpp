// analyse_surface: degenerate clouds, thread-count independence, spatial reordering; PCA normals.

#include "pcsketch/differential/surface.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "pcsketch/core/error.h"
#include "support/analytic_shapes.h"

namespace pcsketch::differential {
namespace {

PointCloud cloud_of(std::vector<Vec3f> positions) {
  PointCloud cloud;
  cloud.positions = std::move(positions);
  return cloud;
}

/// Every output finite, normals unit.
void expect_defined(const PointCloud& cloud, const Surface& surface) {
  ASSERT_EQ(cloud.normals.size(), cloud.size());
  ASSERT_EQ(surface.curvature.k1.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_NEAR(cloud.normals[i].norm(), 1.f, 1e-5f) << i;
    ASSERT_TRUE(std::isfinite(surface.curvature.k1[i]) && std::isfinite(surface.curvature.k2[i])) << i;
    ASSERT_TRUE(surface.curvature.dir1[i].allFinite() && surface.curvature.dir2[i].allFinite()) << i;
    ASSERT_GE(surface.curvature.k1[i], surface.curvature.k2[i]) << i;
  }
  ASSERT_TRUE(std::isfinite(surface.spacing));
}

TEST(Surface, FewerThanThreeDistinctPointsIsAnError) {
  for (std::vector<Vec3f> positions : {std::vector<Vec3f>{}, std::vector<Vec3f>{Vec3f::Ones()},
                                       std::vector<Vec3f>(50, Vec3f(1.f, 2.f, 3.f)),
                                       std::vector<Vec3f>{Vec3f::Zero(), Vec3f::UnitX(), Vec3f::Zero()}}) {
    PointCloud cloud = cloud_of(positions);
    try {
      analyse_surface(cloud);
      FAIL() << positions.size() << " points accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("fewer than 3 distinct"), std::string::npos) << e.what();
    }
  }
}

TEST(Surface, ThreePointsGiveTheirPlane) {
  PointCloud cloud = cloud_of({Vec3f::Zero(), Vec3f::UnitX(), Vec3f::UnitY()});
  const Surface surface = analyse_surface(cloud);
  expect_defined(cloud, surface);
  EXPECT_EQ(surface.neighbourhoods.k, 2u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::abs(cloud.normals[i].z()), 1.f, 1e-6f);
    EXPECT_EQ(cloud.normals[i], cloud.normals[0]);
    EXPECT_EQ(surface.curvature.k1[i], 0.f);
  }
  EXPECT_FALSE(surface.warnings.empty());  // too few points per fit
}

TEST(Surface, CollinearCloudHasPerpendicularNormalsAndWarns) {
  std::vector<Vec3f> line;
  for (int i = 0; i < 200; ++i) line.push_back(Vec3f(1.f, 2.f, 0.5f) * (0.01f * static_cast<float>(i)));
  PointCloud cloud = cloud_of(line);
  const Surface surface = analyse_surface(cloud);
  expect_defined(cloud, surface);
  const Vec3f axis = Vec3f(1.f, 2.f, 0.5f).normalized();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_LT(std::abs(cloud.normals[i].dot(axis)), 1e-4f) << i;
    EXPECT_LT(std::abs(surface.curvature.k1[i]), 1e-3f) << i;
  }
  ASSERT_FALSE(surface.warnings.empty());
  EXPECT_NE(surface.warnings[0].find("collinear"), std::string::npos);
}

TEST(Surface, CoplanarCloudIsFlatWithDuplicates) {
  PointCloud cloud = test::plane(1.f, {.n = 2000, .seed = 1});
  cloud.normals.clear();
  for (std::size_t i = 0; i < 100; ++i) cloud.positions.push_back(cloud.positions[i]);  // exact duplicates
  const Surface surface = analyse_surface(cloud);
  expect_defined(cloud, surface);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_NEAR(std::abs(cloud.normals[i].z()), 1.f, 1e-5f) << i;
    EXPECT_LT(std::abs(surface.curvature.k1[i]), 1e-3f) << i;
  }
  EXPECT_GT(surface.spacing, 0.f);
}

TEST(Surface, FileNormalsKeptUnlessRecomputed) {
  PointCloud cloud = test::sphere(1.f, {.n = 2000, .seed = 4});
  for (Vec3f& n : cloud.normals) n = -2.f * n;  // inward and not unit: kept (normalised), not re-oriented
  PointCloud kept = cloud;
  const Surface surface = analyse_surface(kept);
  EXPECT_FALSE(surface.normals_estimated);
  for (std::size_t i = 0; i < kept.size(); ++i)
    ASSERT_NEAR(kept.normals[i].dot(kept.positions[i].normalized()), -1.f, 1e-5f);
  EXPECT_LT(surface.curvature.k1[0], 0.f);  // inward normals: the sphere reads as concave

  PointCloud oriented = cloud;
  analyse_surface(oriented, {.orient_file_normals = true});
  for (std::size_t i = 0; i < oriented.size(); ++i) ASSERT_GT(oriented.normals[i].dot(oriented.positions[i]), 0.f);

  PointCloud invalid = cloud;
  invalid.normals[5] = Vec3f::Zero();
  const Surface recomputed = analyse_surface(invalid);
  EXPECT_TRUE(recomputed.normals_estimated);
  EXPECT_FALSE(recomputed.warnings.empty());
}

// Normals whose signs are arbitrary (some scanners and converters write them so): their directions are kept, their
// signs re-oriented outward, with a warning. Consistent ones, even all inward, are kept as they are (above).
TEST(Surface, FileNormalsWithArbitrarySignsAreReoriented) {
  PointCloud cloud = test::sphere(1.f, {.n = 4000, .seed = 6});
  const std::vector<Vec3f> exact = cloud.normals;
  for (std::size_t i = 0; i < cloud.size(); i += 3) cloud.normals[i] = -cloud.normals[i];
  const PointCloud flipped = cloud;
  const Surface surface = analyse_surface(cloud);
  EXPECT_FALSE(surface.normals_estimated);
  ASSERT_EQ(surface.warnings.size(), 1u);
  EXPECT_NE(surface.warnings[0].find("not consistently oriented"), std::string::npos) << surface.warnings[0];
  for (std::size_t i = 0; i < cloud.size(); ++i)
    ASSERT_NEAR(cloud.normals[i].dot(exact[cloud.source_index[i]]), 1.f, 1e-5f) << i;

  PointCloud trusted = flipped;
  const Surface as_read = analyse_surface(trusted, {.file_normal_disagreement = 1.0});
  EXPECT_TRUE(as_read.warnings.empty());
  for (std::size_t i = 0; i < trusted.size(); ++i)
    ASSERT_NEAR(trusted.normals[i].dot(flipped.normals[trusted.source_index[i]]), 1.f, 1e-5f) << i;
}

// Consistent file normals of a noisy scan are trusted, raw (0.05%: under the denoising trigger) or denoised. Noise
// stacks some neighbours along their normals, which the reflect test reads as opposed unless it knows the noise: at
// 0.6% the disagreement was 0.07–0.13% of pairs without the noise rule, 0.04–0.10% with it (re-orienting from 1%).
TEST(Surface, NoisyFileNormalsAreTrustedOverSeeds) {
  const float a = 1.f;
  for (const float fraction : {0.0005f, 0.003f, 0.006f})
    for (unsigned seed = 1; seed <= 2; ++seed) {
      SCOPED_TRACE("noise " + std::to_string(fraction) + ", seed " + std::to_string(seed));
      PointCloud cloud = test::cube(a, {.n = 30000, .seed = seed, .noise_sigma = fraction * 2.f * std::sqrt(3.f) * a});
      const std::vector<Vec3f> exact = cloud.normals;
      const Surface surface = analyse_surface(cloud);
      EXPECT_FALSE(surface.normals_estimated);
      for (const std::string& w : surface.warnings) EXPECT_EQ(w.find("not consistently oriented"), std::string::npos) << w;
      for (std::size_t i = 0; i < cloud.size(); ++i)
        ASSERT_GT(cloud.normals[i].dot(exact[cloud.source_index[i]]), 0.f) << i;
    }
}

/// Everything analyse_surface produces, for exact comparison.
struct Snapshot {
  PointCloud cloud;
  Surface surface;
};

Snapshot run(PointCloud cloud, std::size_t threads, bool reorder) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Snapshot s;
  cloud.normals.clear();
  s.surface = analyse_surface(cloud, {.reorder = reorder});
  s.cloud = std::move(cloud);
  return s;
}

TEST(Surface, SameBitsForAnyThreadCount) {
  test::SampleSpec spec{.n = 6000, .seed = 21};
  spec.noise_sigma = 0.004f;  // noisy enough for the adaptive second curvature pass
  const PointCloud torus = test::torus(1.f, 0.3f, spec);
  const Snapshot one = run(torus, 1, true);
  const Snapshot two = run(torus, 2, true);
  const Snapshot four = run(torus, 4, true);
  EXPECT_GT(one.surface.curvature.fit_neighbours, one.surface.neighbourhoods.k);
  for (const Snapshot* other : {&two, &four}) {
    EXPECT_EQ(one.cloud.positions, other->cloud.positions);
    EXPECT_EQ(one.cloud.normals, other->cloud.normals);
    EXPECT_EQ(one.surface.neighbourhoods.indices, other->surface.neighbourhoods.indices);
    EXPECT_EQ(one.surface.neighbourhoods.distances, other->surface.neighbourhoods.distances);
    EXPECT_EQ(one.surface.spacing, other->surface.spacing);
    EXPECT_EQ(one.surface.curvature.k1, other->surface.curvature.k1);
    EXPECT_EQ(one.surface.curvature.k2, other->surface.curvature.k2);
    EXPECT_EQ(one.surface.curvature.dir1, other->surface.curvature.dir1);
    EXPECT_EQ(one.surface.curvature.fit_neighbours, other->surface.curvature.fit_neighbours);
  }
}

TEST(Surface, ReorderingOnlyPermutes) {
  const PointCloud torus = test::torus(1.f, 0.3f, {.n = 6000, .seed = 8});
  const Snapshot plain = run(torus, 2, false);
  const Snapshot sorted = run(torus, 2, true);
  ASSERT_TRUE(plain.cloud.source_index.empty());
  ASSERT_EQ(sorted.cloud.source_index.size(), torus.size());
  EXPECT_EQ(plain.surface.spacing, sorted.surface.spacing);
  for (std::size_t i = 0; i < torus.size(); ++i) {
    const std::size_t j = sorted.cloud.source_index[i];
    ASSERT_EQ(sorted.cloud.positions[i], torus.positions[j]);
    ASSERT_GT(sorted.cloud.normals[i].dot(plain.cloud.normals[j]), 0.99999f) << i;
    ASSERT_NEAR(sorted.surface.curvature.k1[i], plain.surface.curvature.k1[j], 1e-4f) << i;
    ASSERT_NEAR(sorted.surface.curvature.k2[i], plain.surface.curvature.k2[j], 1e-4f) << i;
  }
}

TEST(Normals, PlaneNormalsAndSurfaceVariation) {
  const PointCloud plane = test::plane(1.f, {.n = 3000, .seed = 6});
  const neighbourhood::KdTree tree(plane.positions);
  const auto nb = neighbourhood::compute_neighbourhoods(tree, plane.positions, {.k = 10});
  const NormalResult result = estimate_normals(plane.positions, nb);
  EXPECT_TRUE(result.warnings.empty());
  for (std::size_t i = 0; i < plane.size(); ++i) {
    ASSERT_NEAR(std::abs(result.normals[i].z()), 1.f, 1e-6f);
    ASSERT_LT(result.surface_variation[i], 1e-6f);
  }
  // The corner of a cube: the variation is far from 0 (a crease), but still ≤ 1/3.
  const PointCloud cube = test::cube(1.f, {.n = 6000, .seed = 6});
  const auto cube_nb = neighbourhood::compute_neighbourhoods(neighbourhood::KdTree(cube.positions), cube.positions);
  const NormalResult cube_normals = estimate_normals(cube.positions, cube_nb);
  float largest = 0;
  for (float v : cube_normals.surface_variation) largest = std::max(largest, v);
  EXPECT_GT(largest, 0.05f);
  EXPECT_LE(largest, 1.f / 3.f + 1e-6f);
}

// Two parallel planes 0.05 apart, 4000 points each on [-1, 1]²: a 16-point list reaches about 0.07, so it holds
// points of both (two plates' faces). Each point's normal is its own plane's, and the analysis's lists hold only it.
TEST(Normals, TwoFacesOfAThinPlateKeepTheirOwnNormalsAndLists) {
  constexpr float kGap = 0.05f;
  PointCloud faces = test::plane(1.f, {.n = 4000, .seed = 3});
  for (Vec3f p : test::plane(1.f, {.n = 4000, .seed = 4}).positions) faces.positions.push_back(p + Vec3f(0, 0, kGap));
  faces.normals.clear();
  const auto mixed = neighbourhood::compute_neighbourhoods(neighbourhood::KdTree(faces.positions), faces.positions);
  const float cos_10 = std::cos(10.f * 3.14159265f / 180.f);
  std::size_t reaching = 0, tilted_by_pca = 0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (const std::uint32_t j : mixed.of(i)) reaching += (j < 4000) != (i < 4000);
    // The plain PCA normal over the mixed list.
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    Vec3d mean = faces.positions[i].cast<double>();
    for (const std::uint32_t j : mixed.of(i)) mean += faces.positions[j].cast<double>();
    mean /= static_cast<double>(mixed.k + 1);
    const auto add = [&](const Vec3f& p) {
      covariance += (p.cast<double>() - mean) * (p.cast<double>() - mean).transpose();
    };
    add(faces.positions[i]);
    for (const std::uint32_t j : mixed.of(i)) add(faces.positions[j]);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    tilted_by_pca += std::abs(eigen.eigenvectors().col(0).z()) < cos_10;
  }
  // The premise: the lists mix the two faces, and a plain PCA over them tilts many normals.
  ASSERT_GT(reaching, 2 * faces.size());
  ASSERT_GT(tilted_by_pca, faces.size() / 5);
  PointCloud analysed = faces;
  const Surface surface = analyse_surface(analysed, {});
  EXPECT_GT(surface.own_face_lists, faces.size() / 2);
  std::size_t tilted = 0, crossing = 0;
  for (std::size_t i = 0; i < analysed.size(); ++i) {
    tilted += std::abs(analysed.normals[i].z()) < cos_10;
    const bool upper = analysed.positions[i].z() > 0.5f * kGap;
    for (const std::uint32_t j : surface.neighbourhoods.of(i))
      crossing += (analysed.positions[j].z() > 0.5f * kGap) != upper;
  }
  // Measured: 6695 of the 8000 plain PCA normals over 10° off and 33440 list entries on the other face; now 378 and
  // 2014. Points near the squares' rims, whose lists reach the other face on one side only, may keep a mixed list.
  EXPECT_LT(tilted, analysed.size() / 12);
  EXPECT_LT(crossing, reaching / 10);
}

}  // namespace
}  // namespace pcsketch::differential
