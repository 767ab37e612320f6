#include "pcsketch/stylize/line_finish.h"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace pcsketch::stylize {

namespace {

/// Vertices that do not move: the ends of an open line and the image's corners (local minima of the bend angle
/// below the corner angle).
std::vector<std::uint8_t> pinned_vertices(const Polyline& line, const view::Camera& camera, const FinishOptions& o) {
  const std::size_t n = line.size();
  std::vector<Vec2f> image(n);
  for (std::size_t i = 0; i < n; ++i) image[i] = camera.project(line.points[i]).head<2>();
  // Sparse lines (a coarse mesh's vertices, 15–20 px apart) need an arm of a few segments to see past their steps.
  std::vector<float> segment;
  for (std::size_t i = 0; i + 1 < n; ++i) segment.push_back((image[i + 1] - image[i]).norm());
  std::nth_element(segment.begin(), segment.begin() + static_cast<std::ptrdiff_t>(segment.size() / 2), segment.end());
  const float arm = std::max(o.corner_arm_px, 2.f * segment[segment.size() / 2]);
  const std::vector<float> bend = bend_angles_deg(line, image, arm);
  std::vector<std::uint8_t> pinned(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool end = !line.closed && (i == 0 || i + 1 == n);
    const float before = bend[(i + n - 1) % n], after = bend[(i + 1) % n];
    pinned[i] = end || (bend[i] < o.corner_angle_deg && bend[i] <= before && bend[i] <= after);
  }
  return pinned;
}

}  // namespace

nlohmann::json FinishOptions::to_json() const {
  return {{"smooth", smooth},
          {"smooth_passes", smooth_passes},
          {"corner_angle_deg", corner_angle_deg},
          {"corner_arm_px", corner_arm_px},
          {"min_length_px", min_length_px}};
}

Polyline smooth_line(const Polyline& line, const view::Camera& camera, const FinishOptions& o) {
  Polyline out = line;
  const std::size_t n = line.size();
  if (!o.smooth || n < 3 || o.smooth_passes <= 0) return out;
  const std::vector<std::uint8_t> pinned = pinned_vertices(line, camera, o);
  std::vector<Vec3f> next(n);
  // Taubin's λ|μ: a shrinking step then an inflating one, so curves keep their size while zigzags die out.
  for (int pass = 0; pass < 2 * o.smooth_passes; ++pass) {
    const float step = pass % 2 == 0 ? 0.5f : -0.53f;
    for (std::size_t i = 0; i < n; ++i) {
      if (pinned[i]) {
        next[i] = out.points[i];
        continue;
      }
      const Vec3f mean = 0.5f * (out.points[(i + n - 1) % n] + out.points[(i + 1) % n]);
      next[i] = out.points[i] + step * (mean - out.points[i]);
    }
    out.points.swap(next);
  }
  return out;
}

std::size_t drop_short_strokes(StrokesResult& strokes, const FinishOptions& o) {
  std::size_t kept = 0;
  for (std::size_t s = 0; s < strokes.strokes.size(); ++s) {
    if (strokes.strokes[s].visible && strokes.strokes[s].image_length() < o.min_length_px) continue;
    if (kept != s) {
      strokes.strokes[kept] = std::move(strokes.strokes[s]);
      strokes.line[kept] = strokes.line[s];
    }
    ++kept;
  }
  const std::size_t dropped = strokes.strokes.size() - kept;
  strokes.strokes.resize(kept);
  strokes.line.resize(kept);
  return dropped;
}

}  // namespace pcsketch::stylize
