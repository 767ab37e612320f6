// The whole pipeline on analytic shapes: what each kind of line shows, degenerate clouds, reuse of prepare().

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "pcsketch/pipeline.h"
#include "support/analytic_shapes.h"

namespace pcsketch {
namespace {

std::size_t count(const Drawing& d, LineKind kind, bool visible_only = true) {
  std::size_t n = 0;
  for (const Stroke& s : d.strokes) n += s.kind == kind && (s.visible || !visible_only);
  return n;
}

DrawOptions small_image() {
  DrawOptions o;
  o.camera.width = o.camera.height = 256;
  return o;
}

TEST(Pipeline, CubeSeenFromACornerHasContoursAndRidgesButNoValleys) {
  DrawOptions o = small_image();
  o.camera.direction = Vec3d(-1, -1, -1);
  const DrawResult r = draw(test::cube(1.f, {.n = 12000}), o);
  const Drawing& d = r.drawing;
  EXPECT_EQ(d.width, 256);
  EXPECT_GE(count(d, LineKind::Contour), 1u);
  EXPECT_GE(count(d, LineKind::Ridge), 3u);  // the three edges at the front corner
  EXPECT_EQ(count(d, LineKind::Valley), 0u);
  for (const Stroke& s : d.strokes) {
    ASSERT_EQ(s.image_points.size(), s.points.size());
    EXPECT_EQ(s.half_widths.size(), 2 * s.segments());
    for (const Vec2f& p : s.image_points) {
      EXPECT_GE(p.x(), -1.f);
      EXPECT_LE(p.x(), 257.f);
    }
  }
  EXPECT_EQ(d.camera["projection"], "orthographic");
  EXPECT_GT(d.parameters["resolved"]["spacing_h"].get<double>(), 0.0);
  EXPECT_EQ(d.parameters["thickness"]["rho_max"], o.thickness.rho_max);
  EXPECT_GT(r.timings.ridge_valley_points, 0.0);
  EXPECT_GT(r.timings.total(), 0.0);
}

// --plotter: the same lines, merged and sorted per layer, the pen travel recorded (plotter/plot_order.h).
TEST(Pipeline, PlotterModeOrdersTheStrokesAndRecordsThePenTravel) {
  DrawOptions o = small_image();
  o.camera.direction = Vec3d(-1, -1, -1);
  const Prepared prepared = prepare(test::cube(1.f, {.n = 12000}), o);
  const Drawing plain = draw_view(prepared, o.camera, o).drawing;
  o.render.plotter = true;
  const Drawing plotted = draw_view(prepared, o.camera, o).drawing;
  EXPECT_TRUE(plain.plotter.is_null());
  ASSERT_FALSE(plotted.plotter.is_null());
  const nlohmann::json& before = plotted.plotter["before_ordering"];
  const nlohmann::json& after = plotted.plotter["after_ordering"];
  const plotter::PlotStats stats = plotter::plot_stats(plain, render::mm_per_pixel(plain, o.render));
  EXPECT_EQ(before["strokes"], stats.strokes);
  EXPECT_DOUBLE_EQ(before["pen_up_mm"].get<double>(), stats.pen_up_mm);
  EXPECT_LE(after["pen_up_mm"].get<double>(), before["pen_up_mm"].get<double>());
  EXPECT_EQ(after["strokes"].get<std::size_t>(), plotted.strokes.size());
  EXPECT_GE(count(plotted, LineKind::Ridge), 1u);
  EXPECT_EQ(plotted.parameters["plotter"]["min_stroke_mm"], o.plotter.min_stroke_mm);
}

TEST(Pipeline, SphereHasOneClosedContourAndNoFeatureLines) {
  const DrawResult r = draw(test::sphere(1.f, {.n = 8000}), small_image());
  EXPECT_EQ(count(r.drawing, LineKind::Contour), 1u);
  EXPECT_EQ(count(r.drawing, LineKind::Ridge, false) + count(r.drawing, LineKind::Valley, false), 0u);
}

TEST(Pipeline, TinyCloudGivesAnEmptyDrawingAndAWarning) {
  PointCloud tiny;
  tiny.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const DrawResult r = draw(tiny, small_image());
  EXPECT_TRUE(r.drawing.strokes.empty());
  EXPECT_EQ(r.drawing.width, 256);
  ASSERT_FALSE(r.warnings.empty());

  PointCloud duplicates;
  duplicates.positions.assign(50, Vec3f(1, 2, 3));
  const DrawResult dup = draw(duplicates, small_image());
  EXPECT_TRUE(dup.drawing.strokes.empty());
  EXPECT_FALSE(dup.warnings.empty());

  const DrawResult none = draw(PointCloud{}, small_image());
  EXPECT_TRUE(none.drawing.strokes.empty());
  EXPECT_FALSE(none.warnings.empty());
}

TEST(Pipeline, SecondViewReusesPreparedWorkAndDiffers) {
  const DrawOptions o = small_image();
  const Prepared p = prepare(test::torus(1.f, 0.35f, {.n = 12000}), o);
  ASSERT_TRUE(p.analysed());
  view::CameraOptions along_axis = o.camera;
  along_axis.direction = Vec3d(0, 0, 1);
  view::CameraOptions side = o.camera;
  side.direction = Vec3d(1, 0, 0);
  const DrawResult a = draw_view(p, along_axis, o);
  const DrawResult b = draw_view(p, side, o);
  EXPECT_EQ(a.timings.curvature, 0.0);  // view-independent work is not redone
  EXPECT_GE(count(a.drawing, LineKind::Contour), 2u);  // outer rim and hole
  EXPECT_NE(a.drawing.camera["direction"], b.drawing.camera["direction"]);
}

TEST(Pipeline, StageDrawingsFollowThePapersFigure19Columns) {
  DrawOptions o = small_image();
  o.camera.direction = Vec3d(-1, -1, -1);
  // Column (d) is (b) and (c) stroke for stroke when nothing is fused; with fusion on (below) the fused copies are
  // cut at the ends of their stretches, and (d) still holds every line of (b) and (c), length for length.
  o.fusion.enabled = false;
  const Prepared p = prepare(test::cube(1.f, {.n = 12000}), o);
  const StageDrawings result = stage_drawings(p, o.camera, o);
  const auto& stages = result.stages;
  ASSERT_EQ(stages.size(), 5u);
  EXPECT_EQ(stages[0].first, "b_contours");
  EXPECT_EQ(stages[4].first, "f_shadow");
  const Drawing& contours = stages[0].second;
  const Drawing& ridges = stages[1].second;
  const Drawing& fused = stages[2].second;
  EXPECT_GT(count(contours, LineKind::Contour), 0u);
  EXPECT_EQ(count(contours, LineKind::Ridge, false), 0u);
  EXPECT_EQ(count(ridges, LineKind::Contour, false), 0u);
  EXPECT_GT(count(ridges, LineKind::Ridge), 0u);
  EXPECT_EQ(fused.strokes.size(), contours.strokes.size() + ridges.strokes.size());
  // (d) has one width per stroke, (e) varies it.
  auto width_spread = [](const Drawing& d) {
    float lo = 1e9f, hi = 0;
    for (const Stroke& s : d.strokes)
      for (float w : s.half_widths) lo = std::min(lo, w), hi = std::max(hi, w);
    return hi - lo;
  };
  EXPECT_LT(width_spread(fused), 1e-4f);
  EXPECT_GT(width_spread(stages[3].second), 0.5f);

  o.fusion.enabled = true;
  const StageDrawings with_fusion = stage_drawings(p, o.camera, o);
  auto length = [](const Drawing& d) {
    double sum = 0;
    for (const Stroke& s : d.strokes) sum += s.image_length();
    return sum;
  };
  const auto& f = with_fusion.stages;
  EXPECT_NEAR(length(f[2].second), length(f[0].second) + length(f[1].second), 1e-3 * length(f[2].second));
  std::size_t fused_copies = 0;
  for (const Stroke& s : f[2].second.strokes) fused_copies += s.fused_into.has_value();
  EXPECT_GT(fused_copies, 0u);  // the cube's rims: outline and ridge
}

// A perspective eye beyond the sphere looking away from it: nothing in view. stage_drawings reports what draw_view
// reports for the same camera.
TEST(Pipeline, StageDrawingsReportTheViewsWarnings) {
  const DrawOptions o = small_image();
  const Prepared p = prepare(test::sphere(1.f, {.n = 4000}), o);
  const view::CameraOptions away{
      .projection = view::Projection::Perspective, .eye = Vec3d(0, 0, 5), .target = Vec3d(0, 0, 10)};
  const DrawResult single = draw_view(p, away, o);
  ASSERT_FALSE(single.warnings.empty());
  const StageDrawings stages = stage_drawings(p, away, o);
  EXPECT_EQ(stages.warnings, single.warnings);
  EXPECT_GT(stages.timings.total(), 0.0);
}

TEST(Pipeline, TimingRowsAreThePapersTable2) {
  Timings t;
  t.ridge_valley_points = 1;
  t.contour_connection = 2;
  t.read = 0.5;
  const auto rows = t.table_rows();
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0].first, "ridge-valley points extraction");
  EXPECT_EQ(rows[3].first, "contour line connection");
  EXPECT_EQ(rows[5].first, "total");
  EXPECT_DOUBLE_EQ(rows[5].second, 3.5);
  EXPECT_EQ(t.all_rows().back().second, 3.5);
}

}  // namespace
}  // namespace pcsketch
