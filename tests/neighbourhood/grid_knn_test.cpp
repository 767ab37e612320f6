// The neighbourhoods come mostly from a uniform grid: they must equal brute force and the kd-tree's own lists bit for
// bit on every kind of cloud the grid finds hard (uneven density, isolated points, crowded copies, flat and thin
// clouds), and index_neighbourhoods must hand back a working tree.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <random>

#include "nanoflann_metric.h"
#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/kd_tree.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/neighbourhood/spatial_order.h"

namespace pcsketch::neighbourhood {
namespace {

/// Every point's k nearest by (squared distance, index), itself excluded by index.
void expect_brute_force(const std::vector<Vec3f>& points, const Neighbourhoods& nb, std::size_t step = 1) {
  const std::size_t k = nb.k;
  std::vector<std::pair<float, std::uint32_t>> all;
  for (std::size_t i = 0; i < points.size(); i += step) {
    all.clear();
    for (std::uint32_t j = 0; j < points.size(); ++j)
      if (j != i) all.emplace_back(distance_sq(points[i], points[j]), j);
    std::partial_sort(all.begin(), all.begin() + std::ptrdiff_t(k), all.end());
    for (std::size_t m = 0; m < k; ++m) {
      ASSERT_EQ(nb.of(i)[m], all[m].second) << "point " << i << " neighbour " << m;
      ASSERT_EQ(std::bit_cast<std::uint32_t>(nb.distances_of(i)[m]),
                std::bit_cast<std::uint32_t>(std::sqrt(all[m].first)));
    }
  }
}

/// The rows the kd-tree gives, one query per point.
void expect_tree_rows(const std::vector<Vec3f>& points, const KdTree& tree, const Neighbourhoods& nb) {
  std::vector<std::uint32_t> found;
  std::vector<float> distances;
  for (std::size_t i = 0; i < points.size(); ++i) {
    tree.knn_of_point(i, nb.k, found, distances);
    ASSERT_TRUE(std::equal(found.begin(), found.end(), nb.of(i).begin())) << "point " << i;
    ASSERT_TRUE(std::equal(distances.begin(), distances.end(), nb.distances_of(i).begin())) << "point " << i;
  }
}

/// A unit sphere sampled four times as densely on its upper half, with isolated far points, a small clump and 300
/// copies of one point (a crowded cell), shuffled.
std::vector<Vec3f> hard_sphere(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.f, 1.f);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Vec3f> points;
  while (points.size() < n) {
    const Vec3f p = Vec3f(g(rng), g(rng), g(rng)).normalized();
    if (p.z() > 0 || u(rng) < 0.25f) points.push_back(p);
  }
  for (int i = 0; i < 20; ++i) points.emplace_back(3.f * u(rng) - 1.5f, 3.f * u(rng) - 1.5f, 2.f + 3.f * u(rng));
  for (int i = 0; i < 6; ++i) points.emplace_back(2.f + 1e-3f * u(rng), 0.f, 1e-3f * u(rng));
  for (int i = 0; i < 300; ++i) points.push_back(points[7]);
  std::shuffle(points.begin(), points.end(), rng);
  return points;
}

TEST(GridNeighbourhoods, UnevenSphereWithOutliersAndCopiesMatchesBruteForce) {
  const std::vector<Vec3f> points = hard_sphere(6000, 1);
  const KdTree tree(points);
  for (const std::size_t k : {1u, 8u, 16u, 40u}) {
    SCOPED_TRACE(k);
    const Neighbourhoods nb = compute_neighbourhoods(tree, points, {.k = k});
    expect_brute_force(points, nb, 3);
    expect_tree_rows(points, tree, nb);
  }
}

TEST(GridNeighbourhoods, SpatiallyOrderedDenseSurfaceMatchesTheTree) {
  // The pipeline's case: a cloud in Morton order, most rows answered by the grid.
  std::vector<Vec3f> points = hard_sphere(60000, 2);
  std::vector<Vec3f> ordered;
  for (const std::uint32_t i : spatial_order(points)) ordered.push_back(points[i]);
  std::optional<KdTree> tree;
  const Neighbourhoods nb = index_neighbourhoods(ordered, tree, {.k = 16});
  ASSERT_TRUE(tree.has_value());
  ASSERT_EQ(tree->size(), ordered.size());
  expect_tree_rows(ordered, *tree, nb);
}

TEST(GridNeighbourhoods, FlatThinAndLatticeCloudsMatchBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Vec3f> plane, line, lattice, cube;
  for (int i = 0; i < 3000; ++i) plane.emplace_back(u(rng), u(rng), 0.f);
  for (int i = 0; i < 2000; ++i) line.emplace_back(0.f, 5.f * u(rng), 0.f);
  // Exact ties everywhere: equal distances are ordered by index.
  for (int x = 0; x < 14; ++x)
    for (int y = 0; y < 14; ++y)
      for (int z = 0; z < 14; ++z) lattice.emplace_back(float(x), float(y), float(z));
  for (int i = 0; i < 3000; ++i) cube.emplace_back(u(rng), u(rng), u(rng));
  for (const auto* cloud : {&plane, &line, &lattice, &cube}) {
    const Neighbourhoods nb = compute_neighbourhoods(KdTree(*cloud), *cloud, {.k = 16});
    expect_brute_force(*cloud, nb, 2);
  }
}

TEST(GridNeighbourhoods, TinyCloudsAndAllCopies) {
  const std::vector<Vec3f> copies(40, Vec3f(1.f, 2.f, 3.f));
  std::optional<KdTree> tree;
  const Neighbourhoods same = index_neighbourhoods(copies, tree, {.k = 16});
  expect_brute_force(copies, same);
  const std::vector<Vec3f> few{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
  const Neighbourhoods nb = index_neighbourhoods(few, tree, {.k = 16});
  EXPECT_EQ(nb.k, 3u);
  expect_brute_force(few, nb);
  EXPECT_EQ(index_neighbourhoods({}, tree, {.k = 16}).k, 0u);
}

/// Lists updated after points leave the cloud equal the lists computed afresh, bit for bit: removed far points
/// (no list held them), the clump and some copies (lists that held them), and points scattered over the sphere.
TEST(GridNeighbourhoods, ListsAfterARemovalEqualFreshOnes) {
  const std::vector<Vec3f> sphere = hard_sphere(20000, 6);
  std::vector<Vec3f> all;
  for (const std::uint32_t i : spatial_order(sphere)) all.push_back(sphere[i]);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<std::uint8_t> removed(all.size(), 0);
  for (std::size_t i = 0; i < all.size(); ++i)
    removed[i] = all[i].z() > 1.5f || all[i].x() > 1.5f || u(rng) < 0.01f || (all[i] == all[7] && u(rng) < 0.5f);
  std::vector<Vec3f> kept;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (!removed[i]) kept.push_back(all[i]);
  ASSERT_GT(all.size() - kept.size(), 200u);
  for (const std::size_t k : {1u, 16u, 40u}) {
    SCOPED_TRACE(k);
    std::optional<KdTree> before_tree, updated_tree, fresh_tree;
    const Neighbourhoods before = index_neighbourhoods(all, before_tree, {.k = k});
    const Neighbourhoods updated = neighbourhoods_after_removal(before, removed, kept, updated_tree, {.k = k});
    const Neighbourhoods fresh = index_neighbourhoods(kept, fresh_tree, {.k = k});
    ASSERT_EQ(updated.k, fresh.k);
    EXPECT_EQ(updated.indices, fresh.indices);
    EXPECT_TRUE(std::equal(updated.distances.begin(), updated.distances.end(), fresh.distances.begin(),
                           fresh.distances.end(), [](float a, float b) {
                             return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
                           }));
    ASSERT_TRUE(updated_tree.has_value());
    expect_tree_rows(kept, *updated_tree, updated);
  }
  // Removing all but two points leaves lists of one neighbour: computed afresh.
  std::vector<std::uint8_t> most(all.size(), 1);
  most[0] = most[1] = 0;
  std::optional<KdTree> tree;
  const Neighbourhoods before = index_neighbourhoods(all, tree, {.k = 16});
  const Neighbourhoods two = neighbourhoods_after_removal(before, most, {all[0], all[1]}, tree, {.k = 16});
  EXPECT_EQ(two.k, 1u);
  EXPECT_EQ(std::vector<std::uint32_t>(two.indices.begin(), two.indices.end()), (std::vector<std::uint32_t>{1, 0}));
  EXPECT_THROW(neighbourhoods_after_removal(before, most, {all[0]}, tree, {.k = 16}), Error);
}

/// The distance from point i to its 16th nearest (brute force): a radius on the cloud's own scale.
float gridded_reach(const std::vector<Vec3f>& points, std::size_t i) {
  std::vector<float> d;
  for (const Vec3f& p : points) d.push_back((p - points[i]).norm());
  std::nth_element(d.begin(), d.begin() + 16, d.end());
  return d[16];
}

/// After knn_of_every_point the tree's grid answers its single-point queries first: each must equal what a tree
/// without a grid gives, the k-NN bit for bit and the balls as sets.
void expect_grid_queries_match(const std::vector<Vec3f>& points) {
  const KdTree gridded(points), plain(points);
  compute_neighbourhoods(gridded, points, {.k = 16});
  std::vector<std::uint32_t> a, b;
  std::vector<float> da, db;
  for (std::size_t i = 0; i < points.size(); i += 7) {
    for (const std::size_t k : {1u, 16u, 64u, 256u}) {
      gridded.knn_of_point(i, k, a, da);
      plain.knn_of_point(i, k, b, db);
      ASSERT_EQ(a, b) << "point " << i << ", k " << k;
      ASSERT_TRUE(std::equal(da.begin(), da.end(), db.begin(), db.end())) << "point " << i << ", k " << k;
    }
    const float r = gridded_reach(points, i);
    for (const float radius : {0.f, r, 2.5f * r, 3 * r, 20 * r}) {
      gridded.radius_any_order(points[i], radius, a);
      plain.radius_unsorted(points[i], radius, b);
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      ASSERT_EQ(a, b) << "point " << i << ", radius " << radius;
    }
  }
}

TEST(GridNeighbourhoods, TreeQueriesFromTheGridMatchTheTree) {
  std::vector<Vec3f> ordered;
  const std::vector<Vec3f> sphere = hard_sphere(20000, 4);
  for (const std::uint32_t i : spatial_order(sphere)) ordered.push_back(sphere[i]);
  expect_grid_queries_match(ordered);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Vec3f> lattice, plane;
  for (int x = 0; x < 30; ++x)
    for (int y = 0; y < 30; ++y)
      for (int z = 0; z < 3; ++z) lattice.emplace_back(float(x), float(y), float(z));
  for (int i = 0; i < 5000; ++i) plane.emplace_back(u(rng), u(rng), 0.f);
  expect_grid_queries_match(lattice);
  expect_grid_queries_match(plane);
}

}  // namespace
}  // namespace pcsketch::neighbourhood
