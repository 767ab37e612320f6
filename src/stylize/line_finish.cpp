#include "pcsketch/stylize/line_finish.h"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace pcsketch::stylize {

namespace {

/// Vertices that do not move: the ends of an open line, the image's corners (local minima of the bend angle below
/// the corner angle) and the samples of a sparse line (both segments over 1.5 corner arms).
std::vector<std::uint8_t> pinned_vertices(const Polyline& line, const view::Camera& camera, const FinishOptions& o) {
  const std::size_t n = line.size();
  std::vector<Vec2f> image(n);
  for (std::size_t i = 0; i < n; ++i) image[i] = camera.project(line.points[i]).head<2>();
  // Sparse lines (a coarse mesh's vertices, 15–20 px apart) need an arm of a few segments to see past their steps.
  // Image length of the segment from vertex i to the next (the closing one last).
  std::vector<float> length(n);
  for (std::size_t i = 0; i < n; ++i) length[i] = (image[(i + 1) % n] - image[i]).norm();
  std::vector<float> segment(length.begin(), length.end() - 1);  // the open line's: the median ignores the closing
  std::nth_element(segment.begin(), segment.begin() + static_cast<std::ptrdiff_t>(segment.size() / 2), segment.end());
  const float arm = std::max(o.corner_arm_px, 2.f * segment[segment.size() / 2]);
  const std::vector<float> bend = bend_angles_deg(line, image, arm);
  std::vector<std::uint8_t> pinned(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool end = !line.closed && (i == 0 || i + 1 == n);
    const float before = bend[(i + n - 1) % n], after = bend[(i + 1) % n];
    // A bend between segments over 1.5 arms (12 px; a coarse cloud's outline, 10–20 px apart) is the shape drawn
    // at that sample: smoothed, the vertex clouds' lines left the mesh's rims (contour P and R 0.01–0.06 lower over
    // 3 views of 5 clouds). The stairs of a traced crease step by about a spacing, under 9 px, and are smoothed.
    const bool sparse = !end && std::min(length[(i + n - 1) % n], length[i]) > 1.5f * o.corner_arm_px;
    pinned[i] = end || sparse || (bend[i] < o.corner_angle_deg && bend[i] <= before && bend[i] <= after);
  }
  return pinned;
}

}  // namespace

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
  // Measured per line, not per run: a long line whose visibility flickers keeps its short visible runs (they are
  // where the line is seen), a line seen only over a few pixels goes.
  const std::vector<Stroke>& all = strokes.strokes;
  std::vector<float> visible_length;
  for (std::size_t s = 0; s < all.size(); ++s) {
    if (strokes.line[s] >= visible_length.size()) visible_length.resize(strokes.line[s] + 1, 0.f);
    if (all[s].visible) visible_length[strokes.line[s]] += all[s].image_length();
  }
  auto is_short = [&](std::size_t s) { return all[s].visible && visible_length[strokes.line[s]] < o.min_length_px; };
  // A short piece that starts or ends within join_px of the end of a longer line reads as that line's continuation
  // (a contour broken where it was traced in two parts), not as a dab: it stays, joined to it.
  std::vector<Vec2f> long_ends;
  for (std::size_t s = 0; s < all.size(); ++s)
    if (all[s].visible && !is_short(s) && !all[s].image_points.empty()) {
      long_ends.push_back(all[s].image_points.front());
      long_ends.push_back(all[s].image_points.back());
    }
  auto continues_a_line = [&](const Stroke& st) {
    for (const Vec2f& end : {st.image_points.front(), st.image_points.back()})
      for (const Vec2f& other : long_ends)
        if ((end - other).norm() <= o.join_px) return true;
    return false;
  };
  std::vector<std::uint8_t> drop(all.size(), 0);
  for (std::size_t s = 0; s < all.size(); ++s) drop[s] = is_short(s) && !continues_a_line(all[s]);
  std::size_t kept = 0;
  for (std::size_t s = 0; s < all.size(); ++s) {
    if (drop[s]) continue;
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
