// The page on real drawings: a stated scale measured on the drawn outline, and the alignment of a sheet's views.

#include <gtest/gtest.h>

#include <algorithm>

#include "pcsketch/pipeline.h"
#include "pcsketch/render/options.h"
#include "pcsketch/render/svg.h"
#include "pcsketch/validate.h"
#include "support/analytic_shapes.h"

namespace pcsketch {
namespace {

struct Extent {
  Vec2f min{1e9f, 1e9f}, max{-1e9f, -1e9f};
  Vec2f size() const { return max - min; }
};

/// Extent of the visible contour and ridge points of `d` inside the rectangle [lo, hi).
Extent line_extent(const Drawing& d, const Vec2f& lo = Vec2f(-1e9f, -1e9f), const Vec2f& hi = Vec2f(1e9f, 1e9f)) {
  Extent e;
  for (const Stroke& s : d.strokes) {
    if (!s.visible || s.fused_into || (s.kind != LineKind::Contour && s.kind != LineKind::Ridge)) continue;
    for (const Vec2f& p : s.image_points) {
      if ((p.array() < lo.array()).any() || (p.array() >= hi.array()).any()) continue;
      e.min = e.min.cwiseMin(p);
      e.max = e.max.cwiseMax(p);
    }
  }
  return e;
}

/// A 200 × 120 × 80 box (model units: mm), sampled densely on its faces.
PointCloud box() {
  PointCloud cloud = test::cube(100.f, {.n = 40000});
  for (Vec3f& p : cloud.positions) p = p.cwiseProduct(Vec3f(1.f, 0.6f, 0.4f));
  return cloud;
}

TEST(Page, CubeOf200mmAt1To20IsA10mmSquare) {
  DrawOptions o;
  o.camera.named = view::NamedView::Front;  // along +z: the front face is a 200 mm square
  o.page = {.scale = 1.0 / 20, .units = page::Units::Millimetre, .scale_bar = true};
  o.lines.hatching = false;
  const DrawResult r = draw(test::cube(100.f, {.n = 60000}), o);
  ASSERT_TRUE(r.drawing.page_mm_per_pixel);
  const double mm_per_px = *r.drawing.page_mm_per_pixel;
  const Extent e = line_extent(r.drawing);
  EXPECT_NEAR(e.size().x() * mm_per_px, 10.0, 0.1);
  EXPECT_NEAR(e.size().y() * mm_per_px, 10.0, 0.1);
  // The SVG page is in millimetres at that scale.
  const std::string svg = render::svg_string(r.drawing, o.render);
  char width[64];
  std::snprintf(width, sizeof width, "width=\"%.3fmm\"", r.drawing.width * mm_per_px);
  EXPECT_NE(svg.find(width), std::string::npos) << width;
  EXPECT_NE(svg.find("inkscape:label=\"8 annotations\""), std::string::npos);
  EXPECT_NE(svg.find(">1:20</text>"), std::string::npos);
}

TEST(Page, PerspectiveHasNoScale) {
  DrawOptions o;
  o.camera.projection = view::Projection::Perspective;
  o.page = {.scale = 0.05, .units = page::Units::Millimetre};
  EXPECT_THROW(draw(test::cube(1.f, {.n = 2000}), o), OptionError);
  o.page = {.scale = 0.05};
  o.camera.projection = view::Projection::Orthographic;
  EXPECT_THROW(draw(test::cube(1.f, {.n = 2000}), o), OptionError) << "a scale needs the model's unit";
}

TEST(Page, SheetViewsShareOneScaleAndLineUp) {
  DrawOptions o;
  o.camera.width = o.camera.height = 512;
  o.lines.hatching = false;
  const Prepared prepared = prepare(box(), o);
  for (const page::Arrangement arrangement : {page::Arrangement::ThirdAngle, page::Arrangement::FirstAngle}) {
    const DrawResult r = draw_sheet(prepared, o.camera, arrangement, o);
    const Drawing& d = r.drawing;
    ASSERT_EQ(d.width, 1024);
    ASSERT_EQ(d.height, 1024);
    const bool third = arrangement == page::Arrangement::ThirdAngle;
    // Quarters: third angle has top above front and the right view right of it; first angle the top view below.
    const Vec2f front_at(0, third ? 512 : 0), top_at(0, third ? 0 : 512), side_at(512, front_at.y());
    const Vec2f cell(512, 512);
    const Extent front = line_extent(d, front_at, front_at + cell);
    const Extent top = line_extent(d, top_at, top_at + cell);
    const Extent side = line_extent(d, side_at, side_at + cell);
    // Front 200 × 120, top 200 × 80, side 80 × 120, all at one scale.
    const float scale = front.size().x() / 200.f;
    EXPECT_NEAR(front.size().y() / scale, 120.f, 1.5f);
    EXPECT_NEAR(top.size().x() / scale, 200.f, 1.5f);
    EXPECT_NEAR(top.size().y() / scale, 80.f, 1.5f);
    EXPECT_NEAR(side.size().x() / scale, 80.f, 1.5f);
    EXPECT_NEAR(side.size().y() / scale, 120.f, 1.5f);
    // Top view in the front's columns, side view in its rows.
    EXPECT_NEAR(top.min.x(), front.min.x(), 1.5f);
    EXPECT_NEAR(top.max.x(), front.max.x(), 1.5f);
    EXPECT_NEAR(side.min.y(), front.min.y(), 1.5f);
    EXPECT_NEAR(side.max.y(), front.max.y(), 1.5f);
    EXPECT_EQ(d.camera["views"].size(), 4u);
    EXPECT_EQ(d.parameters["sheet"], third ? "third" : "first");
  }
}

}  // namespace
}  // namespace pcsketch
