#include "pcsketch/core/point_cloud.h"

#include <gtest/gtest.h>

#include "pcsketch/core/assert.h"
#include "pcsketch/core/polyline.h"
#include "support/analytic_shapes.h"

namespace pcsketch {
namespace {

TEST(PointCloud, PermuteKeepsAttributesTogetherAndComposesSourceIndex) {
  PointCloud c = test::cube(1.f, {.n = 10});
  const PointCloud before = c;
  const std::vector<std::uint32_t> order{9, 8, 7, 6, 5, 4, 3, 2, 1, 0};
  permute(c, order);
  permute(c, {1, 0, 2, 3, 4, 5, 6, 7, 8, 9});
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::uint32_t src = c.source_index[i];
    EXPECT_EQ(c.positions[i], before.positions[src]);
    EXPECT_EQ(c.normals[i], before.normals[src]);
  }
  EXPECT_EQ(c.source_index[0], 8u);
  EXPECT_EQ(c.source_index[1], 9u);
  EXPECT_THROW(permute(c, {0, 1}), Error);
}

TEST(PointCloud, BoundingBoxOfCube) {
  const Box3f box = bounding_box(test::cube(2.f, {.n = 5000}).positions);
  EXPECT_NEAR(box.min.x(), -2.f, 1e-6f);
  EXPECT_NEAR(box.max.z(), 2.f, 1e-6f);
  EXPECT_NEAR(box.diagonal(), 4.f * std::sqrt(3.f), 1e-4f);
  EXPECT_TRUE(Box3f{}.empty());
}

TEST(Polyline, LengthCountsClosingSegment) {
  Polyline l;
  l.points = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0)};
  EXPECT_FLOAT_EQ(l.length(), 3.f);
  l.closed = true;
  EXPECT_FLOAT_EQ(l.length(), 4.f);
  EXPECT_EQ(to_string(LineKind::Valley), "valley");
}

TEST(Assert, ThrowsWithLocation) {
  try {
    PCS_ASSERT(1 == 2, "arithmetic");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("point_cloud_test.cpp"), std::string::npos);
  }
}

}  // namespace
}  // namespace pcsketch
