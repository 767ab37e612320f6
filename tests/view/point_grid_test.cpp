// PointGrid's centre-first scan against its scan in grid order: the same points, and the same answer from a stop.

#include "point_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

namespace pcsketch::view::detail {
namespace {

using Vec2 = PointGrid<2>::Vec;

TEST(PointGrid, CentreFirstVisitsTheSamePointsAndStopsAlike) {
  std::mt19937 rng(12111);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Vec2> points(3000);
  for (Vec2& p : points) p = Vec2(u(rng), 0.3f * u(rng));
  const PointGrid<2> grid(points, 0.05f);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec2 q(1.3f * u(rng), 0.4f * u(rng));
    const float radius = 0.2f * (1.f + u(rng));
    std::vector<std::pair<std::uint32_t, float>> in_order, centre_first;
    grid.for_each_within(q, radius, [&](std::uint32_t i, float d2) { in_order.emplace_back(i, d2); });
    EXPECT_TRUE(grid.for_each_within_until_centre_first(q, radius, [&](std::uint32_t i, float d2) {
      centre_first.emplace_back(i, d2);
      return true;
    }));
    std::sort(in_order.begin(), in_order.end());
    std::sort(centre_first.begin(), centre_first.end());
    ASSERT_EQ(in_order, centre_first) << "trial " << trial;
    // A stop after m points: the scan ends early exactly when the radius holds m of them.
    const std::size_t m = 1 + static_cast<std::size_t>(trial % 40);
    std::size_t seen = 0;
    const bool ran_to_end =
        grid.for_each_within_until_centre_first(q, radius, [&](std::uint32_t, float) { return ++seen < m; });
    EXPECT_EQ(ran_to_end, in_order.size() < m) << "trial " << trial;
  }
}

}  // namespace
}  // namespace pcsketch::view::detail
