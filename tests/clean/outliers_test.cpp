// Known answers of the outlier stage: stray points and clumps added to analytic shapes are found, surface points
// (also where the density falls 4:1) are kept.

#include "pcsketch/clean/outliers.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pcsketch/neighbourhood/kd_tree.h"
#include "support/analytic_shapes.h"

namespace pcsketch::clean {
namespace {

struct Count {
  /// Stray points added, and how many of them were left out; the same for those farther than 4 m from every surface
  /// point (m: the cloud's median mean distance to 8 neighbours). Nearer ones cannot be told from surface noise.
  std::size_t outliers = 0, found = 0, far = 0, far_found = 0;
  std::size_t surface = 0, lost = 0;     ///< surface points, and how many of them were left out
};

Count run(const PointCloud& cloud, const OutlierOptions& options = {}) {
  const neighbourhood::KdTree tree(cloud.positions);
  const neighbourhood::Neighbourhoods nbh = neighbourhood::compute_neighbourhoods(tree, cloud.positions);
  const OutlierResult r = find_outliers(cloud.positions, nbh, options);
  std::vector<Vec3f> surface;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (cloud.source_index.empty() || cloud.source_index[i] != test::kOutlier) surface.push_back(cloud.positions[i]);
  const neighbourhood::KdTree surface_tree(surface);
  std::vector<std::uint32_t> index;
  std::vector<float> distance;
  Count c;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const bool stray = !cloud.source_index.empty() && cloud.source_index[i] == test::kOutlier;
    (stray ? c.outliers : c.surface) += 1;
    (stray ? c.found : c.lost) += r.outlier[i];
    if (!stray) continue;
    surface_tree.knn(cloud.positions[i], 1, index, distance);
    if (distance[0] <= 4 * r.median_distance) continue;
    ++c.far;
    c.far_found += r.outlier[i];
  }
  EXPECT_EQ(r.removed(), c.found + c.lost);
  return c;
}

TEST(Outliers, CleanShapesLoseNoPoint) {
  for (const PointCloud& shape : {test::sphere(1.f, {.n = 20000, .seed = 1}), test::cube(1.f, {.n = 20000, .seed = 2}),
                                  test::torus(1.f, 0.3f, {.n = 20000, .seed = 3}),
                                  test::plane(1.f, {.n = 5000, .seed = 4})}) {
    const Count c = run(shape);
    EXPECT_EQ(c.lost, 0u);
  }
}

TEST(Outliers, OnePercentUniformStrayPointsAreLeftOut) {
  for (PointCloud shape : {test::sphere(1.f, {.n = 20000, .seed = 5}), test::cube(1.f, {.n = 20000, .seed = 6}),
                           test::torus(1.f, 0.3f, {.n = 20000, .seed = 7})}) {
    test::add_outliers(shape, 0.01f);
    const Count c = run(shape);
    EXPECT_GE(static_cast<double>(c.far_found), 0.95 * static_cast<double>(c.far)) << c.far_found << "/" << c.far;
    EXPECT_GE(static_cast<double>(c.found), 0.75 * static_cast<double>(c.outliers)) << c.found << "/" << c.outliers;
    EXPECT_LE(static_cast<double>(c.lost), 0.005 * static_cast<double>(c.surface));
  }
}

TEST(Outliers, TwoPercentInClumpsAreLeftOut) {
  for (PointCloud shape : {test::sphere(1.f, {.n = 20000, .seed = 8}), test::cube(1.f, {.n = 20000, .seed = 9}),
                           test::torus(1.f, 0.3f, {.n = 20000, .seed = 10})}) {
    test::add_outliers(shape, 0.02f, 20);
    const Count c = run(shape);
    EXPECT_GE(static_cast<double>(c.far_found), 0.95 * static_cast<double>(c.far)) << c.far_found << "/" << c.far;
    EXPECT_GE(static_cast<double>(c.found), 0.75 * static_cast<double>(c.outliers)) << c.found << "/" << c.outliers;
    EXPECT_LE(static_cast<double>(c.lost), 0.005 * static_cast<double>(c.surface));
  }
}

TEST(Outliers, FourToOneDensityAndNoisyPointsAreSurface) {
  // Three quarters of the x > 0 half dropped: that half has a quarter of the density of the other.
  const PointCloud dense = test::sphere(1.f, {.n = 40000, .seed = 11, .noise_sigma = 0.003f});
  PointCloud uneven;
  for (std::size_t i = 0; i < dense.size(); ++i)
    if (dense.positions[i].x() <= 0 || i % 4 == 0) uneven.positions.push_back(dense.positions[i]);
  EXPECT_EQ(run(uneven).lost, 0u);
}

/// A unit sphere of 40k points with the x > 0 half thinned to one point in 36: d there is about 6 m, over the
/// density factor, as on a coarse mesh's large faces.
PointCloud sphere_with_sparse_half() {
  const PointCloud dense = test::sphere(1.f, {.n = 40000, .seed = 15});
  PointCloud uneven;
  for (std::size_t i = 0; i < dense.size(); ++i)
    if (dense.positions[i].x() <= 0 || i % 36 == 0) uneven.positions.push_back(dense.positions[i]);
  return uneven;
}

TEST(Outliers, ASparseSheetStaysWithTheSurface) {
  const PointCloud uneven = sphere_with_sparse_half();
  EXPECT_EQ(run(uneven).lost, 0u);
  // Without the sheet rule the sparse half falls apart: only its points next to the dense half are kept.
  EXPECT_GT(run(uneven, {.sheet_variation = 0}).lost, 100u);
  // Stray points are still found among the sparse sheet's.
  PointCloud strays = uneven;
  test::add_outliers(strays, 0.01f);
  const Count c = run(strays);
  EXPECT_GE(static_cast<double>(c.far_found), 0.95 * static_cast<double>(c.far)) << c.far_found << "/" << c.far;
  EXPECT_LE(static_cast<double>(c.lost), 0.005 * static_cast<double>(c.surface));
}

TEST(Outliers, APointHoveringOverASparseSheetIsNoSheet) {
  // 20 points a quarter of the radius (about 2.4 sparse spacings) over the sparse half: their 16 nearest lie on the
  // sheet, so only their own offset from its plane tells them apart. The off-surface rule is set aside, so that the
  // sheet's own test is what finds them.
  PointCloud cloud = sphere_with_sparse_half();
  const std::size_t n = cloud.size();
  cloud.source_index.assign(n, 0);
  for (std::size_t i = 0, sparse = 0; i < n && cloud.size() < n + 20; ++i)
    if (cloud.positions[i].x() > 0.3f && sparse++ % 10 == 0) {
      cloud.positions.push_back(1.25f * cloud.positions[i]);
      cloud.source_index.push_back(test::kOutlier);
    }
  ASSERT_EQ(cloud.size(), n + 20);
  const Count c = run(cloud, {.offset_factor = 1e4f});
  EXPECT_EQ(c.found, 20u);
  // Sheet points that hold a hovering point among their 16 nearest may fail the sheet test themselves (13 here).
  EXPECT_LE(static_cast<double>(c.lost), 0.005 * static_cast<double>(c.surface));
}

TEST(Outliers, ALineOfSparsePointsIsNoSheet) {
  // Flying pixels along a ray from the surface: 40 points 8 m apart, a line, not a sheet. They stray from the ray by
  // up to 0.1 m, as measured pixels do, so that only the sheet's second axis tells the line apart (exactly collinear
  // points would leave it to the rounding of a zero eigenvalue).
  PointCloud cloud = test::sphere(1.f, {.n = 20000, .seed = 16});
  const neighbourhood::KdTree tree(cloud.positions);
  const float m =
      find_outliers(cloud.positions, neighbourhood::compute_neighbourhoods(tree, cloud.positions)).median_distance;
  ASSERT_GT(m, 0.f);
  const std::size_t n = cloud.size();
  cloud.source_index.assign(n, 0);
  for (int s = 1; s <= 40; ++s) {
    const float t = static_cast<float>(s);
    cloud.positions.push_back(Vec3f(0.1f * m * std::sin(t), 0.1f * m * std::cos(1.3f * t), 1.f + 8.f * m * t));
    cloud.source_index.push_back(test::kOutlier);
  }
  const Count c = run(cloud);
  EXPECT_EQ(c.lost, 0u);
  EXPECT_GE(c.found, 39u);
}

TEST(Outliers, ASmallCloudIsItsOwnSurface) {
  // Fewer points than the minimum cluster: the largest cluster is kept whatever its size.
  const Count c = run(test::sphere(1.f, {.n = 20, .seed = 12}));
  EXPECT_EQ(c.lost, 0u);
}

// A stray point hovering over a surface has that surface as its neighbours, so only its offset from their plane gives
// it away: on a clean plane the limit is offset_factor × m (2 m), which the stage settles from bounds on the
// offsets, solving the plane of the few points near the limit only. Noise of σ = 0.4 m moves each point's mean, so
// the bounds' median no longer settles the limit: it comes from the median of the exact offsets, over every point
// (8k) or over a sample of 16k (40k points), and the same points are told apart.
TEST(Outliers, HoveringPointsAreOffTheSurfaceBeyondTheLimit) {
  for (const std::size_t points : {8000u, 40000u}) {
    const PointCloud base = test::plane(1.f, {.n = points, .seed = 14});
    const neighbourhood::KdTree base_tree(base.positions);
    const float m =
        find_outliers(base.positions, neighbourhood::compute_neighbourhoods(base_tree, base.positions)).median_distance;
    ASSERT_GT(m, 0.f);
    for (const float sigma : {0.f, 0.4f}) {
      PointCloud cloud = test::plane(1.f, {.n = points, .seed = 14, .noise_sigma = sigma * m});
      const std::size_t n = cloud.size();
      cloud.positions.push_back(Vec3f(0.1f, 0.2f, 1.f * m));   // near: within the limit, as a noisy surface point
      cloud.positions.push_back(Vec3f(-0.3f, 0.1f, 3.f * m));  // dense (under 4 m from its neighbours), off the plane
      const neighbourhood::KdTree tree(cloud.positions);
      const neighbourhood::Neighbourhoods nbh = neighbourhood::compute_neighbourhoods(tree, cloud.positions);
      const OutlierResult r = find_outliers(cloud.positions, nbh);
      EXPECT_FALSE(r.outlier[n]) << points << " points, sigma " << sigma;
      EXPECT_TRUE(r.outlier[n + 1]) << points << " points, sigma " << sigma;
      EXPECT_EQ(r.removed(), 1u) << points << " points, sigma " << sigma;
      // Only the offset gives it away: without the rule it is a surface point.
      EXPECT_EQ(find_outliers(cloud.positions, nbh, {.offset_factor = 1e4f}).removed(), 0u)
          << points << " points, sigma " << sigma;
    }
  }
}

TEST(Outliers, OffKeepsEverything) {
  PointCloud sphere = test::sphere(1.f, {.n = 5000, .seed = 13});
  test::add_outliers(sphere, 0.05f);
  EXPECT_EQ(run(sphere, {.enabled = false}).found, 0u);
}

}  // namespace
}  // namespace pcsketch::clean
