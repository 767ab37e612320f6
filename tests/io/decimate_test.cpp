// Voxel thinning: known survivors on a grid, the same result for any point order, and max_points reached with the
// smallest cell.

#include "pcsketch/io/decimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "io_test_util.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io {
namespace {

// A 10 x 10 grid of spacing 1 in the plane z = 0, with colours and an attribute that name each point.
PointCloud grid() {
  PointCloud cloud;
  PointAttribute id{"id", {}};
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      cloud.positions.emplace_back(float(x), float(y), 0.f);
      cloud.colors.push_back({std::uint8_t(x), std::uint8_t(y), 0});
      id.values.push_back(float(10 * y + x));
    }
  cloud.attributes.push_back(std::move(id));
  return cloud;
}

TEST(Decimate, KeepsThePointNearestEachCellCentre) {
  PointCloud cloud = grid();
  const DecimateReport report = decimate(cloud, {.voxel = 2.0});
  EXPECT_EQ(report.points_before, 100u);
  EXPECT_EQ(report.points_after, 25u);
  EXPECT_EQ(report.cell, 2.0);
  ASSERT_EQ(cloud.size(), 25u);
  // Cell [0,2)^2 has its centre at (1, 1): the survivors are the points with odd x and odd y, in file order.
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3f p = cloud.positions[i];
    EXPECT_EQ(int(p.x()) % 2, 1) << i;
    EXPECT_EQ(int(p.y()) % 2, 1) << i;
    EXPECT_EQ(cloud.colors[i], (Rgb8{std::uint8_t(p.x()), std::uint8_t(p.y()), 0}));  // arrays stay aligned
    EXPECT_EQ(cloud.attributes[0].values[i], 10 * p.y() + p.x());
  }
  EXPECT_TRUE(std::is_sorted(cloud.attributes[0].values.begin(), cloud.attributes[0].values.end()));
}

TEST(Decimate, TheSamePointsForAnyInputOrder) {
  PointCloud a = grid();
  PointCloud b = grid();
  std::vector<std::uint32_t> order(b.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(12111));
  permute(b, order);
  decimate(a, {.voxel = 3.0});
  decimate(b, {.voxel = 3.0});
  std::vector<float> ids_a = a.attributes[0].values, ids_b = b.attributes[0].values;
  std::sort(ids_b.begin(), ids_b.end());
  EXPECT_EQ(ids_a, ids_b);
}

TEST(Decimate, MaxPointsTakesTheSmallestCellThatGetsThere) {
  PointCloud cloud = grid();
  const DecimateReport report = decimate(cloud, {.max_points = 30});
  EXPECT_LE(report.points_after, 30u);
  EXPECT_GT(report.points_after, 8u);
  PointCloud finer = grid();
  EXPECT_GT(decimate(finer, {.voxel = report.cell / 1.002}).points_after, 30u);
  PointCloud small = grid();
  EXPECT_EQ(decimate(small, {.max_points = 100}).points_after, 100u);  // already small enough
}

TEST(Decimate, BadOptionsAreErrors) {
  PointCloud cloud = grid();
  EXPECT_THROW(decimate(cloud, {.voxel = 0.0}), Error);
  EXPECT_THROW(decimate(cloud, {.max_points = 3}), Error);
}

TEST(Decimate, AppliedAtLoadAfterTheCrop) {
  std::string text;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) text += std::to_string(x) + " " + std::to_string(y) + " 0\n";
  const ReadResult r = read_point_cloud_from_memory(
      text, "grid.xyz", {.crop = CropBox{{0, 0, -1}, {3.5, 9, 1}}, .decimate = {.voxel = 2.0}});
  EXPECT_EQ(r.dropped_by_filter, 60u);  // x = 4 … 9
  ASSERT_TRUE(r.decimation.has_value());
  EXPECT_EQ(r.decimation->points_before, 40u);
  EXPECT_EQ(r.decimation->points_after, 10u);
  EXPECT_EQ(r.cloud.size(), 10u);
}

}  // namespace
}  // namespace pcsketch::io
