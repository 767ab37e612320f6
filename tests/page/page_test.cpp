#include "pcsketch/page/page.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "pcsketch/core/error.h"
#include "support/analytic_shapes.h"

namespace pcsketch::page {
namespace {

TEST(Page, ParsesScales) {
  EXPECT_DOUBLE_EQ(parse_scale("1:20"), 0.05);
  EXPECT_DOUBLE_EQ(parse_scale("2:1"), 2.0);
  EXPECT_DOUBLE_EQ(parse_scale("1:2.5"), 0.4);
  for (const char* bad : {"20", "1:0", "-1:20", "1:", ":20", "1:20x", "a:b", "1:inf", ""})
    EXPECT_THROW(parse_scale(bad), Error) << bad;
}

Drawing blank(int width, int height) {
  Drawing d;
  d.width = width;
  d.height = height;
  return d;
}

TEST(Page, StatedScaleSetsMillimetresPerPixel) {
  Drawing d = blank(1000, 800);
  // 4 pixels per model unit (cm), drawn at 1:20: one pixel is 0.25 cm of model = 2.5 mm, 0.125 mm on the page.
  annotate(d, 4.0, std::nullopt, {.scale = 0.05, .units = Units::Centimetre});
  ASSERT_TRUE(d.page_mm_per_pixel);
  EXPECT_DOUBLE_EQ(*d.page_mm_per_pixel, 0.125);
  EXPECT_EQ(d.height, 800) << "no band without a bar or an arrow";
  EXPECT_TRUE(d.annotations.empty());
}

TEST(Page, ScaleBarIsARoundLengthAtTheViewsScale) {
  Drawing d = blank(1000, 800);
  const double pixels_per_unit = 7.3;
  annotate(d, pixels_per_unit, std::nullopt, {.scale = 0.01, .units = Units::Metre, .scale_bar = true});
  EXPECT_GT(d.height, 800) << "the bar sits in a band under the drawing";
  ASSERT_FALSE(d.annotations.lines.empty());
  const std::vector<Vec2f>& outline = d.annotations.lines[0];
  float left = outline[0].x(), right = outline[0].x();
  for (const Vec2f& p : outline) {
    left = std::min(left, p.x());
    right = std::max(right, p.x());
    EXPECT_GE(p.y(), 800.f) << "inside the band";
  }
  const double length = (right - left) / pixels_per_unit;  // model units
  // 1000 px at 7.3 px/unit is 137 units wide; the bar is the roundest length up to 30% of it: 20 units.
  EXPECT_NEAR(length, 20.0, 1e-3);
  std::vector<std::string> texts;
  for (const Label& l : d.annotations.labels) texts.push_back(l.text);
  EXPECT_NE(std::find(texts.begin(), texts.end(), "20 m"), texts.end());
  EXPECT_NE(std::find(texts.begin(), texts.end(), "1:100"), texts.end());
  EXPECT_EQ(d.annotations.fills.size(), 2u) << "4 cells of 5 units, alternately filled";
}

TEST(Page, NorthArrowPointsAlongPlusY) {
  // Looking down −z with y up the image: north is straight up the image (−v).
  view::CameraOptions top;
  top.direction = Vec3d(0, 0, -1);
  const PointCloud cloud = test::plane(1.f, {.n = 500});
  const view::Camera camera = view::make_camera(cloud.positions, Vec3d::Zero(), top);
  const std::optional<Vec2f> north = north_in_image(camera);
  ASSERT_TRUE(north);
  EXPECT_NEAR(north->x(), 0.f, 1e-5f);
  EXPECT_NEAR(north->y(), -1.f, 1e-5f);

  Drawing d = blank(camera.width, camera.height);
  EXPECT_TRUE(annotate(d, camera.scale, north, {.north_arrow = true}).empty());
  ASSERT_EQ(d.annotations.fills.size(), 1u);  // the arrow head
  const auto& head = d.annotations.fills[0];
  const auto& shaft = d.annotations.lines[0];
  EXPECT_LT(head[0].y(), shaft[0].y()) << "the tip is above the tail";

  // Looking along y there is no north to show: a warning, no arrow.
  view::CameraOptions along_y;
  along_y.direction = Vec3d(0, 1, 0);
  along_y.up = Vec3d(0, 0, 1);
  const view::Camera side = view::make_camera(cloud.positions, Vec3d::Zero(), along_y);
  Drawing e = blank(side.width, side.height);
  EXPECT_FALSE(annotate(e, side.scale, north_in_image(side), {.north_arrow = true}).empty());
  EXPECT_TRUE(e.annotations.empty());
}

TEST(Page, SheetViewsFollowTheArrangement) {
  EXPECT_EQ(sheet_views(Arrangement::ThirdAngle)[2], view::NamedView::Right);
  EXPECT_EQ(sheet_views(Arrangement::FirstAngle)[2], view::NamedView::Left);
  EXPECT_EQ(parse_arrangement("first"), Arrangement::FirstAngle);
  EXPECT_FALSE(parse_arrangement("second"));
}

}  // namespace
}  // namespace pcsketch::page
