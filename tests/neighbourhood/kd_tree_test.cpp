// kd-tree queries against brute force, neighbourhoods, spacing and spatial order.

#include "pcsketch/neighbourhood/kd_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/neighbourhood/spacing.h"
#include "pcsketch/neighbourhood/spatial_order.h"
#include "nanoflann_metric.h"

namespace pcsketch::neighbourhood {
namespace {

/// Random points in the unit cube, then duplicates: every 10th point copied once and point 3 copied 30 times.
std::vector<Vec3f> random_points_with_duplicates(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Vec3f> points(n);
  for (Vec3f& p : points) p = Vec3f(u(rng), u(rng), u(rng));
  for (std::size_t i = 0; i < n; i += 10) points.push_back(points[i]);
  for (int c = 0; c < 30; ++c) points.push_back(points[3]);
  std::shuffle(points.begin(), points.end(), rng);
  return points;
}

/// All (squared distance, index) pairs sorted lexicographically.
std::vector<std::pair<float, std::uint32_t>> brute_force(const std::vector<Vec3f>& points, const Vec3f& q) {
  std::vector<std::pair<float, std::uint32_t>> all(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) all[i] = {distance_sq(q, points[i]), static_cast<std::uint32_t>(i)};
  std::sort(all.begin(), all.end());
  return all;
}

TEST(KdTree, KnnMatchesBruteForceWithTiesInIndexOrder) {
  const std::vector<Vec3f> points = random_points_with_duplicates(3000, 42);
  const KdTree tree(points);
  ASSERT_EQ(tree.size(), points.size());
  std::mt19937 rng(12111);
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  std::vector<std::uint32_t> indices;
  std::vector<float> distances;
  for (int q = 0; q < 300; ++q) {
    // Data points (many with duplicates) and off-data queries.
    const Vec3f query = q % 2 ? points[pick(rng)] : Vec3f(points[pick(rng)] + Vec3f(0.01f, -0.003f, 0.002f));
    const auto truth = brute_force(points, query);
    for (std::size_t k : {1, 7, 16, 45}) {
      tree.knn(query, k, indices, distances);
      ASSERT_EQ(indices.size(), k);
      for (std::size_t m = 0; m < k; ++m) {
        ASSERT_EQ(indices[m], truth[m].second) << "query " << q << " k " << k << " rank " << m;
        ASSERT_EQ(distances[m], std::sqrt(truth[m].first));
      }
    }
  }
}

TEST(KdTree, RadiusMatchesBruteForceInclusive) {
  const std::vector<Vec3f> points = random_points_with_duplicates(3000, 7);
  const KdTree tree(points);
  std::vector<std::uint32_t> indices;
  std::vector<float> distances;
  for (std::size_t q = 0; q < 200; ++q) {
    const Vec3f& query = points[q * 13 % points.size()];
    const auto truth = brute_force(points, query);
    // Radius exactly at the distance of the 20th point: that point (and its ties) must be included.
    const float radius = std::sqrt(truth[19].first);
    tree.radius(query, radius, indices, distances);
    std::size_t expected = 0;
    while (expected < truth.size() && std::sqrt(truth[expected].first) <= radius) ++expected;
    ASSERT_EQ(indices.size(), expected) << q;
    ASSERT_GE(indices.size(), 20u);
    for (std::size_t m = 0; m < expected; ++m) ASSERT_EQ(indices[m], truth[m].second) << q;
    ASSERT_TRUE(std::is_sorted(distances.begin(), distances.end()));
  }
}

TEST(KdTree, SmallTrees) {
  const std::vector<Vec3f> none;
  const KdTree empty(none);
  std::vector<std::uint32_t> indices{1, 2};
  std::vector<float> distances{1.f};
  empty.knn(Vec3f::Zero(), 5, indices, distances);
  EXPECT_TRUE(indices.empty());
  const std::vector<Vec3f> two{Vec3f::Zero(), Vec3f::UnitX()};
  const KdTree tree(two);
  tree.knn(Vec3f::Zero(), 5, indices, distances);
  EXPECT_EQ(indices, (std::vector<std::uint32_t>{0, 1}));
  tree.knn_of_point(1, 5, indices, distances);
  EXPECT_EQ(indices, (std::vector<std::uint32_t>{0}));
  EXPECT_THROW(tree.knn_of_point(2, 1, indices, distances), Error);
}

TEST(Neighbourhoods, SelfExcludedByIndexAmongDuplicates) {
  std::vector<Vec3f> points(20, Vec3f(1.f, 2.f, 3.f));  // 20 identical points
  for (int i = 0; i < 50; ++i) points.emplace_back(static_cast<float>(i) * 0.1f, 5.f, 0.f);
  const KdTree tree(points);
  const Neighbourhoods nb = compute_neighbourhoods(tree, points, {.k = 16});
  ASSERT_EQ(nb.k, 16u);
  ASSERT_EQ(nb.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto list = nb.of(i);
    EXPECT_EQ(std::count(list.begin(), list.end(), static_cast<std::uint32_t>(i)), 0) << i;
    EXPECT_TRUE(std::is_sorted(nb.distances_of(i).begin(), nb.distances_of(i).end()));
    if (i < 20) {
      for (std::size_t m = 0; m < 16; ++m) EXPECT_EQ(nb.distances_of(i)[m], 0.f);
    }
  }
  // Neighbours of duplicate 0 are the next duplicates in index order.
  EXPECT_EQ(nb.of(0)[0], 1u);
  EXPECT_EQ(nb.of(5)[0], 0u);
}

TEST(Neighbourhoods, SmallCloudsShrinkK) {
  const std::vector<Vec3f> three{Vec3f::Zero(), Vec3f::UnitX(), Vec3f::UnitY()};
  const Neighbourhoods nb = compute_neighbourhoods(KdTree(three), three, {.k = 16});
  EXPECT_EQ(nb.k, 2u);
  EXPECT_EQ(nb.size(), 3u);
  EXPECT_EQ(nb.of(0)[0], 1u);  // tie (both at distance 1) in index order
  EXPECT_EQ(nb.of(0)[1], 2u);
  const std::vector<Vec3f> one{Vec3f::Zero()};
  EXPECT_EQ(compute_neighbourhoods(KdTree(one), one).k, 0u);
  const std::vector<Vec3f> other{Vec3f::Zero(), Vec3f::UnitX()};
  EXPECT_THROW(compute_neighbourhoods(KdTree(three), other), Error);
}

TEST(Spacing, GridWithDuplicatesAndAnOutlier) {
  std::vector<Vec3f> points;
  for (int x = 0; x < 30; ++x)
    for (int y = 0; y < 30; ++y) points.emplace_back(0.5f * static_cast<float>(x), 0.5f * static_cast<float>(y), 0.f);
  points.push_back(points[17]);  // duplicates do not count as spacing 0
  points.push_back(points[400]);
  points.emplace_back(1000.f, 0.f, 0.f);  // an isolated outlier is among the 1% dropped
  const Neighbourhoods nb = compute_neighbourhoods(KdTree(points), points, {.k = 8});
  EXPECT_NEAR(mean_spacing(nb), 0.5f, 1e-6f);
  const std::vector<Vec3f> same(10, Vec3f::Ones());
  EXPECT_EQ(mean_spacing(compute_neighbourhoods(KdTree(same), same)), 0.f);
}

TEST(SpatialOrder, PermutationThatSourceIndexMapsBack) {
  const std::vector<Vec3f> points = random_points_with_duplicates(5000, 3);
  const std::vector<std::uint32_t> order = spatial_order(points);
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::uint32_t> identity(points.size());
  std::iota(identity.begin(), identity.end(), 0u);
  ASSERT_EQ(sorted, identity);

  PointCloud cloud;
  cloud.positions = points;
  reorder_spatially(cloud);
  ASSERT_EQ(cloud.source_index.size(), points.size());
  double jump_before = 0, jump_after = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(cloud.positions[i], points[cloud.source_index[i]]);
    if (i > 0) {
      jump_before += (points[i] - points[i - 1]).norm();
      jump_after += (cloud.positions[i] - cloud.positions[i - 1]).norm();
    }
  }
  EXPECT_LT(jump_after, 0.2 * jump_before);  // consecutive points are close in space
}

}  // namespace
}  // namespace pcsketch::neighbourhood
