#include "pcsketch/plotter/plot_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "pcsketch/core/error.h"

namespace pcsketch::plotter {
namespace {

constexpr double kMmPerPx = 0.25;  // a 1000 px drawing on a 250 mm page

Stroke stroke(LineKind kind, std::vector<Vec2f> image, bool closed = false) {
  Stroke s;
  s.kind = kind;
  s.closed = closed;
  for (const Vec2f& p : image) s.points.emplace_back(p.x(), p.y(), 0.f);
  s.image_points = std::move(image);
  s.widths.assign(s.image_points.size(), 1.f);
  s.half_widths.assign(2 * s.segments(), 1.f);
  return s;
}

Drawing drawing(std::vector<Stroke> strokes) {
  Drawing d;
  d.width = d.height = 1000;
  d.strokes = std::move(strokes);
  return d;
}

/// Every drawn segment as an unordered pair of rounded end points, sorted: the drawing's ink, whatever the order
/// and direction of its strokes.
using Segment = std::array<long, 4>;
std::vector<Segment> segments(const Drawing& d) {
  std::vector<Segment> out;
  for (const Stroke& s : d.strokes) {
    const std::size_t n = s.image_points.size();
    for (std::size_t i = 0; i + 1 < n + (s.closed ? 1 : 0); ++i) {
      auto key = [](const Vec2f& p) { return std::array<long, 2>{std::lround(p.x() * 1e3), std::lround(p.y() * 1e3)}; };
      auto a = key(s.image_points[i]), b = key(s.image_points[(i + 1) % n]);
      if (b < a) std::swap(a, b);
      out.push_back({a[0], a[1], b[0], b[1]});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Random polylines cut into pieces at random vertices, shuffled and some reversed: merging has ends to join.
std::vector<Stroke> random_pieces(std::mt19937& rng, std::size_t lines, LineKind kind) {
  std::uniform_real_distribution<float> coord(0.f, 1000.f), step(-20.f, 20.f);
  std::vector<Stroke> pieces;
  for (std::size_t l = 0; l < lines; ++l) {
    std::vector<Vec2f> line{{coord(rng), coord(rng)}};
    const std::size_t n = 2 + rng() % 12;
    while (line.size() < n) line.push_back(line.back() + Vec2f(step(rng), step(rng)));
    std::size_t begin = 0;
    while (begin + 1 < line.size()) {
      const std::size_t end = std::min(line.size() - 1, begin + 1 + rng() % 4);
      std::vector<Vec2f> piece(line.begin() + static_cast<long>(begin), line.begin() + static_cast<long>(end) + 1);
      if (rng() % 2) std::reverse(piece.begin(), piece.end());
      pieces.push_back(stroke(kind, piece));
      begin = end;
    }
  }
  std::shuffle(pieces.begin(), pieces.end(), rng);
  return pieces;
}

TEST(PlotOrder, RandomStrokeSetsTravelLessAndKeepEverySegment) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    SCOPED_TRACE(trial);
    std::vector<Stroke> strokes = random_pieces(rng, 50 + 20 * static_cast<std::size_t>(trial), LineKind::Contour);
    const std::vector<Stroke> ridges = random_pieces(rng, 30, LineKind::Ridge);
    strokes.insert(strokes.end(), ridges.begin(), ridges.end());
    const Drawing input = drawing(strokes);
    // Tolerance 0 joins only ends that coincide, and nothing is dropped: the ink must be exactly the same.
    const PlotterResult r = plot_order(input, kMmPerPx, {.merge_tolerance_mm = 0, .min_stroke_mm = 0});
    EXPECT_LE(r.after.pen_up_mm, r.before.pen_up_mm);
    EXPECT_LT(r.after.pen_up_mm, 0.5 * r.before.pen_up_mm);  // greedy ordering of random strokes: far less
    EXPECT_EQ(r.before.pen_up_mm, plot_stats(input, kMmPerPx).pen_up_mm);
    EXPECT_NEAR(r.after.pen_down_mm, r.before.pen_down_mm, 1e-6 * r.before.pen_down_mm);
    EXPECT_LT(r.after.strokes, r.before.strokes);
    EXPECT_EQ(r.after.strokes, r.drawing.strokes.size());
    EXPECT_EQ(segments(r.drawing), segments(input));
    for (const Stroke& s : r.drawing.strokes) {
      EXPECT_EQ(s.points.size(), s.image_points.size());
      EXPECT_EQ(s.widths.size(), s.image_points.size());
      EXPECT_EQ(s.half_widths.size(), 2 * s.segments());
    }
  }
}

// The pieces of one polyline, shuffled and reversed, become that polyline again: one stroke, no pen-up.
TEST(PlotOrder, PiecesOfOneLineMergeIntoOneStroke) {
  const Drawing d =
      drawing({stroke(LineKind::Contour, {{30, 0}, {20, 0}}), stroke(LineKind::Contour, {{0, 0}, {10, 0}}),
               stroke(LineKind::Contour, {{20, 0}, {10, 0.04f}}), stroke(LineKind::Contour, {{30.1f, 0}, {40, 5}})});
  const PlotterResult r = plot_order(d, kMmPerPx, {.min_stroke_mm = 0});
  ASSERT_EQ(r.drawing.strokes.size(), 1u);
  EXPECT_EQ(r.joins, 3u);
  EXPECT_EQ(r.after.pen_up_mm, 0.0);
  const std::vector<Vec2f>& q = r.drawing.strokes[0].image_points;
  // 10,0 and 10,0.04 are within 0.1 mm (0.4 px): joined by a connecting segment; 30,0 and 30.1,0 likewise.
  ASSERT_EQ(q.size(), 7u);
  EXPECT_EQ(q.front(), Vec2f(0, 0));  // sorted from the page origin
  EXPECT_EQ(q.back(), Vec2f(40, 5));
}

TEST(PlotOrder, GreedyOrderFromTheOriginReversingStrokes) {
  // Separate strokes along a row; the nearest end is always the next stroke's left end, or its right end for the
  // reversed ones.
  const Drawing d = drawing({stroke(LineKind::Ridge, {{50, 0}, {40, 0}}), stroke(LineKind::Ridge, {{0, 0}, {10, 0}}),
                             stroke(LineKind::Ridge, {{25, 0}, {20, 0}})});
  const PlotterResult r = plot_order(d, kMmPerPx, {.min_stroke_mm = 0});
  ASSERT_EQ(r.drawing.strokes.size(), 3u);
  EXPECT_EQ(r.drawing.strokes[0].image_points, (std::vector<Vec2f>{{0, 0}, {10, 0}}));
  EXPECT_EQ(r.drawing.strokes[1].image_points, (std::vector<Vec2f>{{20, 0}, {25, 0}}));
  EXPECT_EQ(r.drawing.strokes[2].image_points, (std::vector<Vec2f>{{40, 0}, {50, 0}}));
  EXPECT_DOUBLE_EQ(r.after.pen_up_mm, 25 * kMmPerPx);          // 10 → 20 and 25 → 40
  EXPECT_DOUBLE_EQ(r.before.pen_up_mm, (40 + 15) * kMmPerPx);  // 40 → 0 and 10 → 25
}

// A greedy nearest-end order on thousands of strokes, checked against the brute-force search it replaces.
TEST(PlotOrder, GridSortMatchesBruteForceGreedy) {
  std::mt19937 rng(12111);
  std::uniform_real_distribution<float> coord(0.f, 1000.f);
  std::vector<Stroke> strokes;
  for (int i = 0; i < 3000; ++i) {
    const Vec2f a(coord(rng), coord(rng));
    strokes.push_back(stroke(LineKind::Valley, {a, a + Vec2f(coord(rng), coord(rng)) * 0.01f}));
  }
  const PlotterResult r = plot_order(drawing(strokes), kMmPerPx, {.min_stroke_mm = 0, .merge = false});
  std::vector<std::uint8_t> used(strokes.size(), 0);
  Vec2f pen(0, 0);
  ASSERT_EQ(r.drawing.strokes.size(), strokes.size());
  for (const Stroke& got : r.drawing.strokes) {
    double best = 1e300;
    std::size_t best_i = 0;
    bool reversed = false;
    for (std::size_t i = 0; i < strokes.size(); ++i) {
      if (used[i]) continue;
      for (int end = 0; end < 2; ++end) {
        const Vec2f& p = end == 0 ? strokes[i].image_points.front() : strokes[i].image_points.back();
        const double d = (p - pen).cast<double>().squaredNorm();
        if (d < best) {
          best = d;
          best_i = i;
          reversed = end == 1;
        }
      }
    }
    used[best_i] = 1;
    std::vector<Vec2f> expected = strokes[best_i].image_points;
    if (reversed) std::reverse(expected.begin(), expected.end());
    ASSERT_EQ(got.image_points, expected);
    pen = expected.back();
  }
}

// Attached hatching families 180° apart lay the same lines: overlapping collinear pieces are drawn once.
TEST(PlotOrder, CollinearDuplicateHatchingIsDrawnOnce) {
  const Drawing d = drawing({stroke(LineKind::Hatch, {{0, 0}, {10, 10}}), stroke(LineKind::Hatch, {{20, 20}, {5, 5}}),
                             stroke(LineKind::Hatch, {{0, 0}, {10, 10}}),
                             stroke(LineKind::Hatch, {{0, 2}, {10, 12}}),      // parallel, 1.4 px away: kept
                             stroke(LineKind::Hatch, {{40, 40}, {50, 50}})});  // same line, apart: kept
  const PlotterResult r = plot_order(d, kMmPerPx, {.merge_tolerance_mm = 0, .min_stroke_mm = 0});
  ASSERT_EQ(r.drawing.strokes.size(), 3u);
  const double drawn_twice = 10 * std::sqrt(2.0) + 5 * std::sqrt(2.0);  // the copy of 0–10, and 5–10 again
  EXPECT_NEAR(r.duplicate_hatching_mm, drawn_twice * kMmPerPx, 1e-4);
  EXPECT_NEAR(r.before.pen_down_mm - r.after.pen_down_mm, drawn_twice * kMmPerPx, 1e-4);
  std::vector<Segment> expected =
      segments(drawing({stroke(LineKind::Hatch, {{0, 0}, {20, 20}}), stroke(LineKind::Hatch, {{0, 2}, {10, 12}}),
                        stroke(LineKind::Hatch, {{40, 40}, {50, 50}})}));
  EXPECT_EQ(segments(r.drawing), expected);
  // Contours are never treated so: two identical contour strokes stay two (merged end to end).
  const Drawing contours =
      drawing({stroke(LineKind::Contour, {{0, 0}, {10, 10}}), stroke(LineKind::Contour, {{0, 0}, {10, 10}})});
  EXPECT_EQ(plot_order(contours, kMmPerPx, {.min_stroke_mm = 0}).after.pen_down_mm,
            plot_stats(contours, kMmPerPx).pen_down_mm);
}

TEST(PlotOrder, DabsAreLeftOutAndLayersStayApart) {
  const Drawing d = drawing({stroke(LineKind::Contour, {{0, 0}, {1, 0}}),      // 0.25 mm: a dab
                             stroke(LineKind::Contour, {{100, 0}, {110, 0}}),  // 2.5 mm
                             stroke(LineKind::Ridge, {{110, 0}, {120, 0}}),    // meets the contour: other layer
                             stroke(LineKind::Contour, {{0, 50}, {10, 50}, {10, 60}}, true)});
  const PlotterResult r = plot_order(d, kMmPerPx);  // default: strokes under 0.5 mm left out
  EXPECT_EQ(r.short_strokes_dropped, 1u);
  EXPECT_EQ(r.joins, 0u);
  ASSERT_EQ(r.drawing.strokes.size(), 3u);
  EXPECT_EQ(r.drawing.strokes[0].kind, LineKind::Ridge);  // paint order: ridges under contours
  EXPECT_TRUE(r.drawing.strokes[1].closed);               // the loop's start is nearest the origin
  EXPECT_EQ(r.drawing.strokes[1].image_points.front(), Vec2f(0, 50));
}

TEST(PlotOrder, HiddenStrokesArePlottedOnlyWhenDrawn) {
  Stroke hidden = stroke(LineKind::Contour, {{0, 0}, {100, 0}});
  hidden.visible = false;
  Stroke bad = stroke(LineKind::Contour, {{0, 0}, {std::numeric_limits<float>::quiet_NaN(), 0}});
  const Drawing d = drawing({hidden, bad, stroke(LineKind::Contour, {{0, 10}, {100, 10}})});
  EXPECT_EQ(plot_order(d, kMmPerPx).drawing.strokes.size(), 1u);
  EXPECT_EQ(plot_order(d, kMmPerPx, {}, /*hidden_drawn=*/true).drawing.strokes.size(), 2u);
  EXPECT_EQ(plot_stats(d, kMmPerPx).strokes, 1u);
  EXPECT_TRUE(plot_order(drawing({}), kMmPerPx).drawing.strokes.empty());
  EXPECT_THROW(plot_order(d, 0.0), Error);
}

// Hand-built drawings may hold anything finite: ends far from each other, or all on one spot, still sort.
TEST(PlotOrder, ExtremeCoordinatesStillSort) {
  std::vector<Stroke> strokes;
  for (int i = 0; i < 5; ++i) strokes.push_back(stroke(LineKind::Contour, {{1e30f, 1e30f}, {1e30f, 1e30f}}));
  strokes.push_back(stroke(LineKind::Contour, {{0, 0}, {0, 1e-30f}}));
  strokes.push_back(stroke(LineKind::Contour, {{-3e38f, 0}, {3e38f, 0}}));
  const PlotterResult r = plot_order(drawing(strokes), kMmPerPx, {.merge_tolerance_mm = 0, .min_stroke_mm = 0});
  EXPECT_EQ(r.drawing.strokes.size(), 3u);  // the five dots at one spot are joined into one
  EXPECT_LE(r.after.pen_up_mm, r.before.pen_up_mm);
}

}  // namespace
}  // namespace pcsketch::plotter
