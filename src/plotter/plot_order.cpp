#include "pcsketch/plotter/plot_order.h"

#include <array>
#include <cmath>
#include <deque>
#include <nlohmann/json.hpp>

#include "pcsketch/core/assert.h"
#include "pcsketch/core/error.h"
#include "end_grid.h"
#include "stroke_ops.h"

namespace pcsketch::plotter {

namespace {

using detail::first_point;
using detail::last_point;

// The SVG layers a pen plots, in paint order (render/paint.cpp): hidden lines, hatching, valleys, ridges,
// boundaries, contours.
constexpr std::size_t kLayers = 6;
constexpr std::size_t kNotPlotted = kLayers;

std::size_t layer_of(const Stroke& s, bool hidden_drawn) {
  if (s.image_points.empty() || s.fused_into) return kNotPlotted;  // a fused copy is drawn as its winner

  for (const Vec2f& p : s.image_points)
    if (!p.allFinite()) return kNotPlotted;
  if (!s.visible) return hidden_drawn && s.kind != LineKind::Hatch ? 0 : kNotPlotted;
  switch (s.kind) {
    case LineKind::Hatch:
      return 1;
    case LineKind::Valley:
      return 2;
    case LineKind::Ridge:
      return 3;
    case LineKind::Boundary:
      return 4;
    case LineKind::Contour:
      return 5;
  }
  return kNotPlotted;
}

using Layers = std::array<std::vector<Stroke>, kLayers>;

Layers plotted_layers(const Drawing& d, bool hidden_drawn) {
  Layers layers;
  for (const Stroke& s : d.strokes) {
    const std::size_t layer = layer_of(s, hidden_drawn);
    if (layer != kNotPlotted) layers[layer].push_back(s);
  }
  return layers;
}

/// Pen-up travel through the strokes in their order, pixels.
double travel_px(const std::vector<Stroke>& strokes) {
  double travel = 0;
  for (std::size_t i = 1; i < strokes.size(); ++i)
    travel += (first_point(strokes[i]) - last_point(strokes[i - 1])).norm();
  return travel;
}

PlotStats stats_of(const Layers& layers, double mm_per_pixel) {
  PlotStats stats;
  for (const std::vector<Stroke>& layer : layers) {
    for (const Stroke& s : layer) stats.pen_down_mm += detail::image_length(s) * mm_per_pixel;
    stats.pen_up_mm += travel_px(layer) * mm_per_pixel;
    stats.strokes += layer.size();
  }
  return stats;
}

/// The ends of every stroke in a grid: id 2i is stroke i's start, 2i + 1 its end. Closed strokes keep only their
/// start (they cannot be reversed into another stroke, and begin and end at the same point).
detail::EndGrid end_grid(const std::vector<Stroke>& strokes) {
  std::vector<Vec2d> ends;
  ends.reserve(2 * strokes.size());
  for (const Stroke& s : strokes) {
    ends.push_back(first_point(s));
    ends.push_back(last_point(s));
  }
  detail::EndGrid grid(std::move(ends));
  for (std::size_t i = 0; i < strokes.size(); ++i)
    if (strokes[i].closed) grid.remove(2 * i + 1);
  return grid;
}

/// vpype's linemerge: each stroke in input order, still unused, grows at its end and then at its start by the
/// unused stroke with the nearest end within `tolerance`, reversed when that end faces the wrong way.
std::vector<Stroke> merge_ends(std::vector<Stroke> strokes, double tolerance, std::size_t& joins) {
  detail::EndGrid grid = end_grid(strokes);
  std::vector<std::uint8_t> used(strokes.size(), 0);
  auto take = [&](std::size_t i) {
    used[i] = 1;
    grid.remove(2 * i);
    grid.remove(2 * i + 1);
  };
  std::vector<Stroke> out;
  for (std::size_t i = 0; i < strokes.size(); ++i) {
    if (used[i]) continue;
    take(i);
    if (strokes[i].closed) {
      out.push_back(std::move(strokes[i]));
      continue;
    }
    std::deque<std::size_t> chain{i};
    for (bool at_end : {true, false}) {
      for (;;) {
        const Stroke& tip = strokes[at_end ? chain.back() : chain.front()];
        const std::size_t id = grid.nearest(at_end ? last_point(tip) : first_point(tip), tolerance);
        if (id == detail::EndGrid::npos) break;
        const std::size_t k = id / 2;
        take(k);
        // Growing the end, stroke k must start there; growing the start, it must end there.
        if ((id % 2 == 1) == at_end) detail::reverse(strokes[k]);
        at_end ? chain.push_back(k) : chain.push_front(k);
        ++joins;
      }
    }
    Stroke merged = std::move(strokes[chain.front()]);
    for (std::size_t c = 1; c < chain.size(); ++c) detail::append(merged, strokes[chain[c]]);
    out.push_back(std::move(merged));
  }
  return out;
}

/// vpype's linesort: from the page origin, always the stroke with the nearest end next, reversed when that is its
/// end.
std::vector<Stroke> sort_greedy(std::vector<Stroke> strokes) {
  detail::EndGrid grid = end_grid(strokes);
  std::vector<Stroke> out;
  out.reserve(strokes.size());
  Vec2d pen = Vec2d::Zero();
  while (out.size() < strokes.size()) {
    const std::size_t id = grid.nearest(pen);
    PCS_ASSERT(id != detail::EndGrid::npos, "plotter: a stroke end went missing from the grid");
    const std::size_t k = id / 2;
    grid.remove(2 * k);
    grid.remove(2 * k + 1);
    if (id % 2 == 1 && !strokes[k].closed) detail::reverse(strokes[k]);
    pen = last_point(strokes[k]);
    out.push_back(std::move(strokes[k]));
  }
  return out;
}

/// One layer in plotting order; the input layer itself when the result would travel farther (greedy orders can).
std::vector<Stroke> order_layer(const std::vector<Stroke>& input, double mm_per_pixel, const PlotterOptions& o,
                                PlotterResult& result) {
  std::vector<Stroke> strokes = input;
  double removed_px = 0;
  strokes = detail::merge_collinear(std::move(strokes), o.collinear_tolerance_mm / mm_per_pixel, removed_px);
  std::size_t joins = 0;
  if (o.merge) strokes = merge_ends(std::move(strokes), o.merge_tolerance_mm / mm_per_pixel, joins);
  std::vector<Stroke> kept;
  std::size_t dropped = 0;
  for (Stroke& s : strokes) {
    if (detail::image_length(s) * mm_per_pixel < o.min_stroke_mm)
      ++dropped;
    else
      kept.push_back(std::move(s));
  }
  if (o.sort) kept = sort_greedy(std::move(kept));
  if (travel_px(kept) > travel_px(input)) return input;
  result.duplicate_hatching_mm += removed_px * mm_per_pixel;
  result.joins += joins;
  result.short_strokes_dropped += dropped;
  return kept;
}

}  // namespace

nlohmann::json PlotStats::to_json() const {
  return {{"pen_down_mm", pen_down_mm}, {"pen_up_mm", pen_up_mm}, {"strokes", strokes}};
}

PlotStats plot_stats(const Drawing& drawing, double mm_per_pixel, bool hidden_drawn) {
  return stats_of(plotted_layers(drawing, hidden_drawn), mm_per_pixel);
}

PlotterResult plot_order(const Drawing& drawing, double mm_per_pixel, const PlotterOptions& options,
                         bool hidden_drawn) {
  if (!(mm_per_pixel > 0) || !std::isfinite(mm_per_pixel))
    throw Error("plotter: millimetres per pixel must be positive, got " + number(mm_per_pixel));
  PlotterResult result;
  const Layers input = plotted_layers(drawing, hidden_drawn);
  result.before = stats_of(input, mm_per_pixel);
  Layers ordered;
  for (std::size_t layer = 0; layer < kLayers; ++layer)
    ordered[layer] = order_layer(input[layer], mm_per_pixel, options, result);
  result.after = stats_of(ordered, mm_per_pixel);
  result.drawing = drawing;
  result.drawing.strokes.clear();
  for (std::vector<Stroke>& layer : ordered)
    for (Stroke& s : layer) result.drawing.strokes.push_back(std::move(s));
  return result;
}

}  // namespace pcsketch::plotter
