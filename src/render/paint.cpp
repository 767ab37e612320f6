#include "paint.h"

#include <algorithm>
#include <cmath>

#include "pcsketch/core/error.h"

namespace pcsketch::render::detail {

namespace {

constexpr int kContours = 0, kRidges = 1, kValleys = 2, kHatching = 3, kShading = 4, kHidden = 5, kBoundaries = 6;
constexpr int kLayers = 7;
// The border of open scans came after the first six: it takes the next number, so no earlier layer is renamed.
constexpr std::array<std::string_view, kLayers> kLabels = {"1 contours", "2 ridges", "3 valleys",   "4 hatching",
                                                           "5 shading",  "6 hidden", "7 boundaries"};
// Fills under lines, hidden lines under visible ones, contours last so the outline stays crisp on top.
constexpr std::array<int, kLayers> kPaintOrder = {kShading, kHidden,     kHatching, kValleys,
                                                  kRidges,  kBoundaries, kContours};

int layer_of(LineKind kind) {
  switch (kind) {
    case LineKind::Contour: return kContours;
    case LineKind::Ridge: return kRidges;
    case LineKind::Valley: return kValleys;
    case LineKind::Hatch: return kHatching;
    case LineKind::Boundary: return kBoundaries;
  }
  return kContours;
}

bool finite(const std::vector<Vec2f>& points) {
  for (const Vec2f& p : points)
    if (!p.allFinite()) return false;
  return true;
}

/// Segments of the stroke's image polyline (the renderer draws image_points; 3D points may be absent).
std::size_t segments(const Stroke& s) {
  const std::size_t n = s.image_points.size();
  return n < 2 ? 0 : n - 1 + (s.closed ? 1 : 0);
}

/// Width of half-segment h (2 per segment): the stroke's half_widths, else its per-vertex widths, else the default.
float half_width(const Stroke& s, std::size_t h, const RenderOptions& o) {
  if (s.half_widths.size() == 2 * segments(s)) return s.half_widths[h];
  if (s.widths.size() == s.image_points.size()) {
    const std::size_t v = (h / 2 + h % 2) % s.image_points.size();
    return s.widths[v];
  }
  return o.default_width;
}

float quantised(float w, float step) {
  w = std::isfinite(w) ? std::max(w, 0.f) : 0.f;
  return step > 0 ? std::round(w / step) * step : w;
}

/// The stroke as runs of equal (rounded) width: half-segment 2i goes from point i to the midpoint of segment i, 2i+1
/// from that midpoint to point i+1; the midpoint is only a vertex where the width changes.
std::vector<Run> width_runs(const Stroke& s, const RenderOptions& o) {
  const std::vector<Vec2f>& q = s.image_points;
  const std::size_t count = segments(s);
  const float grey = std::clamp(s.grey, 0.f, 1.f);
  if (count == 0) return {Run{{q[0], q[0]}, false, quantised(half_width(s, 0, o), o.width_step), grey}};
  std::vector<Run> runs;
  for (std::size_t seg = 0; seg < count; ++seg) {
    const Vec2f& a = q[seg];
    const Vec2f& b = q[(seg + 1) % q.size()];
    const Vec2f mid = 0.5f * (a + b);
    for (int half = 0; half < 2; ++half) {
      const float w = quantised(half_width(s, 2 * seg + half, o), o.width_step);
      const Vec2f& start = half == 0 ? a : mid;
      const Vec2f& end = half == 0 ? mid : b;
      if (runs.empty() || runs.back().width != w) {
        runs.push_back(Run{{start}, false, w, grey});
      } else if (half == 1) {
        runs.back().points.pop_back();  // the midpoint is interior to a straight piece of equal width
      }
      runs.back().points.push_back(end);
    }
  }
  if (runs.size() == 1 && s.closed) {
    runs[0].points.pop_back();  // the last point is the first again: close the path instead
    runs[0].closed = true;
  }
  return runs;
}

}  // namespace

std::vector<PaintLayer> paint_layers(const Drawing& d, const RenderOptions& o) {
  std::array<PaintLayer, kLayers> layers;
  for (int i = 0; i < kLayers; ++i) {
    layers[i].number = i + 1;
    layers[i].label = kLabels[i];
  }
  for (std::size_t i = 0; i < d.strokes.size(); ++i) {
    const Stroke& s = d.strokes[i];
    if (s.image_points.empty() || !finite(s.image_points) || s.fused_into) continue;
    PaintStroke ps{i, {}};
    int layer = layer_of(s.kind);
    if (!s.visible) {
      if (o.hidden_lines == HiddenLines::None || s.kind == LineKind::Hatch) continue;
      layer = kHidden;
      std::vector<Vec2f> pts = s.image_points;
      if (pts.size() == 1) pts.push_back(pts[0]);
      ps.runs.push_back(Run{std::move(pts), s.closed && s.image_points.size() > 2, o.hidden_width, o.hidden_grey, true});
    } else if (o.plotter) {
      std::vector<Vec2f> pts = s.image_points;
      if (pts.size() == 1) pts.push_back(pts[0]);
      ps.runs.push_back(Run{std::move(pts), s.closed && s.image_points.size() > 2, pen_width_px(d, o), 0.f});
    } else {
      ps.runs = width_runs(s, o);
    }
    layers[layer].strokes.push_back(std::move(ps));
  }
  if (o.shading && !o.plotter)
    for (std::size_t i = 0; i < d.regions.size(); ++i)
      if (d.regions[i].polygon.size() >= 3 && finite(d.regions[i].polygon)) layers[kShading].regions.push_back(i);

  std::vector<PaintLayer> ordered;
  ordered.reserve(layers.size());
  for (int i : kPaintOrder) ordered.push_back(std::move(layers[i]));
  return ordered;
}

std::array<double, 2> page_size_pt(const Drawing& d, const RenderOptions& o) {
  if (d.width <= 0 || d.height <= 0) throw Error("render: drawing size must be positive");
  // CSS pixel: 1/96 in = 0.75 pt; a millimetre is 72/25.4 pt.
  const double pt_per_px = mm_per_pixel(d, o) * 72.0 / 25.4;
  if (!(pt_per_px > 0) || !std::isfinite(pt_per_px)) throw Error("render: page width must be positive");
  return {d.width * pt_per_px, d.height * pt_per_px};
}

}  // namespace pcsketch::render::detail
