#include "pcsketch/stylize/thickness.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "pcsketch/core/assert.h"
#include "pcsketch/core/error.h"

namespace pcsketch::stylize {

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

/// Cumulative image arc length at each vertex; the last entry (index #L) is the total including the closing segment
/// of a closed line.
std::vector<float> arc_lengths(const std::vector<Vec2f>& pts, bool closed) {
  const std::size_t n = pts.size();
  std::vector<float> s(n + 1, 0.f);
  for (std::size_t i = 1; i < n; ++i) s[i] = s[i - 1] + (pts[i] - pts[i - 1]).norm();
  s[n] = s[n - 1] + (closed && n > 1 ? (pts[0] - pts[n - 1]).norm() : 0.f);
  return s;
}

/// Point at arc length `a` along the polyline (closed lines: a taken modulo the perimeter; open: clamped).
Vec2f point_at(const std::vector<Vec2f>& pts, const std::vector<float>& s, bool closed, float a) {
  const std::size_t n = pts.size();
  const float total = s[n];
  if (closed && total > 0.f) {
    a = std::fmod(a, total);
    if (a < 0.f) a += total;
  } else {
    a = std::clamp(a, 0.f, s[n - 1]);
  }
  // Segment j runs from s[j] to s[j + 1]; j = n − 1 is the closing segment.
  const std::size_t segs = closed ? n : n - 1;
  auto it = std::upper_bound(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(segs) + 1, a);
  std::size_t j = it == s.begin() ? 0 : static_cast<std::size_t>(it - s.begin()) - 1;
  j = std::min(j, segs - 1);
  const float len = s[j + 1] - s[j];
  const float f = len > 0.f ? (a - s[j]) / len : 0.f;
  return pts[j] + f * (pts[(j + 1) % n] - pts[j]);
}

/// Angle in degrees at `p` between the directions to `a` and `b` (eq. 9); 180 when either arm is degenerate.
template <class V>
float angle_between(const V& a, const V& p, const V& b) {
  const V u = a - p, v = b - p;
  const double nu = u.norm(), nv = v.norm();
  if (!(nu > 0) || !(nv > 0)) return 180.f;
  const double c = std::clamp(static_cast<double>(u.dot(v)) / (nu * nv), -1.0, 1.0);
  return static_cast<float>(std::acos(c) * kRadToDeg);
}

/// Brush taper factor for every vertex: a quarter-sine ramp from `end_fraction` at both ends to 1.
std::vector<float> taper(const std::vector<Vec2f>& image_points, const ThicknessOptions& o) {
  const std::vector<float> s = arc_lengths(image_points, false);
  const std::size_t n = image_points.size();
  const float total = s[n - 1];
  const float len = std::min(o.brush_taper_px, 0.5f * total);
  std::vector<float> f(n, 1.f);
  if (!(len > 0.f)) return f;
  for (std::size_t i = 0; i < n; ++i) {
    const float from_end = std::min(s[i], total - s[i]);
    const float x = std::min(from_end / len, 1.f);
    f[i] = o.brush_end_fraction + (1.f - o.brush_end_fraction) * std::sin(0.5f * std::numbers::pi_v<float> * x);
  }
  return f;
}

void check(const ThicknessOptions& o) {
  if (!(o.rho_min >= 0.f) || !(o.rho_max >= o.rho_min))
    throw Error("stylize/thickness: need 0 <= rho_min <= rho_max (got " + std::to_string(o.rho_min) + ", " +
                std::to_string(o.rho_max) + ")");
  if (!(o.cofi >= 0.f) || !(o.angle_arm_px >= 0.f) || !(o.brush_taper_px >= 0.f) ||
      !(o.brush_end_fraction >= 0.f && o.brush_end_fraction <= 1.f) ||
      !(o.angle_weight >= 0.f && o.angle_weight <= 1.f))
    throw Error(
        "stylize/thickness: cofi, angle arm and taper length must be >= 0; brush end fraction and angle "
        "weight in [0, 1]");
}

/// An optional extra vertex at one end of a visibility run: the midpoint shared with the neighbouring run.
struct RunEnd {
  bool has_mid = false;
  Vec3f point = Vec3f::Zero();
  float width = 0.f;
};

}  // namespace

int angle_level(double alpha_deg) {
  // Upper bin edges of Table 1 in degrees (π/9, π/6, 2π/9, 5π/18, π/3, 4π/9, 5π/9, 2π/3, 5π/6), level 10 first.
  static constexpr std::array<double, 9> kEdges = {20, 30, 40, 50, 60, 80, 100, 120, 150};
  int level = 10;
  for (double edge : kEdges) {
    if (alpha_deg <= edge) return level;
    --level;
  }
  return 1;
}

std::vector<float> bend_angles_deg(const Polyline& line, const std::vector<Vec2f>& image_points, float arm_px) {
  const std::size_t n = line.size();
  PCS_ASSERT(image_points.size() == n, "bend_angles_deg: one image point per vertex");
  std::vector<float> alpha(n, 180.f);
  if (n < 3) return alpha;
  if (arm_px <= 0.f) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!line.closed && (i == 0 || i + 1 == n)) continue;
      alpha[i] = angle_between(line.points[(i + n - 1) % n], line.points[i], line.points[(i + 1) % n]);
    }
    return alpha;
  }
  const std::vector<float> s = arc_lengths(image_points, line.closed);
  const float total = s[n];
  // A closed loop shorter than two arms would compare a vertex with itself.
  const float arm = line.closed ? std::min(arm_px, 0.45f * total) : arm_px;
  for (std::size_t i = 0; i < n; ++i) {
    float back = arm, ahead = arm;
    if (!line.closed) {
      back = std::min(arm, s[i]);
      ahead = std::min(arm, s[n - 1] - s[i]);
    }
    if (back < 0.5f * arm_px || ahead < 0.5f * arm_px || !(arm > 0.f)) continue;
    const Vec2f a = point_at(image_points, s, line.closed, s[i] - back);
    const Vec2f b = point_at(image_points, s, line.closed, s[i] + ahead);
    alpha[i] = angle_between(a, image_points[i], b);
  }
  return alpha;
}

DepthRange depth_range(const std::vector<Polyline>& lines, const view::Camera& camera) {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (const Polyline& l : lines)
    for (const Vec3f& p : l.points) {
      const float z = camera.project(p).z();
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  if (lo > hi) return {};
  return {lo, hi};
}

std::vector<float> stroke_widths(const Polyline& line, const std::vector<Vec3f>& projected, const DepthRange& range,
                                 const ThicknessOptions& o) {
  const std::size_t n = line.size();
  PCS_ASSERT(projected.size() == n, "stroke_widths: one projected point per vertex");
  check(o);
  const float span = o.rho_max - o.rho_min;
  std::vector<Vec2f> image(n);
  for (std::size_t i = 0; i < n; ++i) image[i] = projected[i].head<2>();

  std::vector<float> depth_w(n, o.rho_min + 0.5f * span), angle_w(n, o.rho_min);
  if (o.model == ThicknessModel::Depth || o.model == ThicknessModel::Combined) {
    // Eqs. 1–3 with "nearer is thicker" (the text of §V.A; eq. 3 as printed grows with depth and lacks ρ_min).
    const float extent = range.far - range.near;
    for (std::size_t i = 0; i < n; ++i) {
      const float f = extent > 0.f ? std::clamp((range.far - projected[i].z()) / extent, 0.f, 1.f) : 0.5f;
      depth_w[i] = o.rho_min + f * span;
    }
  }
  if (o.model == ThicknessModel::Angle || o.model == ThicknessModel::Combined) {
    const std::vector<float> alpha = bend_angles_deg(line, image, o.angle_arm_px);
    for (std::size_t i = 0; i < n; ++i) {
      const int level = angle_level(alpha[i]);
      angle_w[i] = o.angle_width == AngleWidth::Range ? o.rho_min + static_cast<float>(level - 1) / 9.f * span
                                                      : static_cast<float>(level) / 10.f * o.rho_max;
    }
  }

  std::vector<float> w(n);
  for (std::size_t i = 0; i < n; ++i) {
    switch (o.model) {
      case ThicknessModel::Constant:
      case ThicknessModel::Depth:
        w[i] = depth_w[i];
        break;
      case ThicknessModel::Angle:
        w[i] = angle_w[i];
        break;
      case ThicknessModel::Combined:
        w[i] = o.combination == Combination::Mean ? (1.f - o.angle_weight) * depth_w[i] + o.angle_weight * angle_w[i]
                                                  : (o.rho_max > 0.f ? depth_w[i] * angle_w[i] / o.rho_max : 0.f);
        break;
    }
  }
  if (o.brush && !line.closed && n >= 2) {
    const std::vector<float> f = taper(image, o);
    for (std::size_t i = 0; i < n; ++i) w[i] *= f[i];
  }
  for (float& x : w) x *= o.cofi;
  return w;
}

std::vector<float> half_segment_widths(const std::vector<float>& widths, bool closed, bool normalise_cofi) {
  const std::size_t n = widths.size();
  const std::size_t segs = n < 2 ? 0 : n - 1 + (closed ? 1 : 0);
  const float f = normalise_cofi ? 2.f / 3.f : 1.f;
  std::vector<float> halves(2 * segs);
  for (std::size_t i = 0; i < segs; ++i) {
    const float t_front = widths[i], t_p = widths[(i + 1) % n];
    halves[2 * i] = (t_front + 0.5f * t_p) * f;      // eq. 4 / 10
    halves[2 * i + 1] = (0.5f * t_front + t_p) * f;  // eq. 5 / 11
  }
  return halves;
}

namespace {

/// Appends the stroke of `count` vertices of `line` from `first` (indices modulo #L), with optional shared midpoints.
void add_run(std::vector<Stroke>& out, const Polyline& line, const std::vector<Vec3f>& projected,
             const std::vector<float>& widths, std::size_t first, std::size_t count, const RunEnd& head,
             const RunEnd& tail, bool visible, bool closed, const view::Camera& camera, bool normalise) {
  Stroke s;
  s.kind = line.kind;
  s.visible = visible;
  s.closed = closed;
  auto push = [&](const Vec3f& p, const Vec2f& uv, float w) {
    s.points.push_back(p);
    s.image_points.push_back(uv);
    s.widths.push_back(w);
  };
  if (head.has_mid) push(head.point, camera.project(head.point).head<2>(), head.width);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = (first + k) % line.size();
    push(line.points[i], projected[i].head<2>(), widths[i]);
  }
  if (tail.has_mid) push(tail.point, camera.project(tail.point).head<2>(), tail.width);
  if (s.points.size() < 2) return;
  s.half_widths = half_segment_widths(s.widths, s.closed, normalise);
  out.push_back(std::move(s));
}

/// Strokes of one line: split into runs of equal visibility that share the midpoint of each changing segment.
std::vector<Stroke> line_strokes(const Polyline& line, const std::vector<std::uint8_t>& flags,
                                 const view::Camera& camera, const DepthRange& range, const ThicknessOptions& o) {
  std::vector<Stroke> out;
  const std::size_t n = line.size();
  if (n < 2) return out;
  std::vector<Vec3f> projected(n);
  for (std::size_t i = 0; i < n; ++i) projected[i] = camera.project(line.points[i]);
  const std::vector<float> widths = stroke_widths(line, projected, range, o);
  auto vis = [&](std::size_t i) { return flags.empty() || flags[i % n] != 0; };

  std::size_t first_change = n;
  for (std::size_t i = 1; i < n && first_change == n; ++i)
    if (vis(i) != vis(i - 1)) first_change = i;
  if (first_change == n && (!line.closed || vis(n - 1) == vis(0))) {
    add_run(out, line, projected, widths, 0, n, {}, {}, vis(0), line.closed, camera, o.normalise_cofi);
    return out;
  }
  // A closed line starts at a visibility change, so that its wrap is an ordinary run boundary.
  const std::size_t start = line.closed && vis(n - 1) == vis(0) ? first_change : 0;

  auto midpoint = [&](std::size_t a, std::size_t b) {
    return RunEnd{true, 0.5f * (line.points[a] + line.points[b]), 0.5f * (widths[a] + widths[b])};
  };
  // A closed line's first run begins at the midpoint of the segment that wraps into `start`.
  RunEnd head = line.closed ? midpoint((start + n - 1) % n, start) : RunEnd{};
  std::size_t run_first = start, run_count = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (start + k) % n;
    ++run_count;
    const bool last = k + 1 == n;
    const std::size_t next = (i + 1) % n;
    const bool has_next = !last || line.closed;
    if (has_next && vis(next) != vis(i)) {
      const RunEnd mid = midpoint(i, next);
      add_run(out, line, projected, widths, run_first, run_count, head, mid, vis(i), false, camera, o.normalise_cofi);
      head = mid;
      run_first = next;
      run_count = 0;
    } else if (last) {
      add_run(out, line, projected, widths, run_first, run_count, head, {}, vis(i), false, camera, o.normalise_cofi);
    }
  }
  return out;
}

}  // namespace

StrokesResult make_strokes(const std::vector<Polyline>& lines, const view::Camera& camera,
                           const std::vector<std::vector<std::uint8_t>>& visible, const ThicknessOptions& o) {
  check(o);
  if (!visible.empty() && visible.size() != lines.size())
    throw Error("stylize/make_strokes: visibility given for " + std::to_string(visible.size()) + " lines, expected " +
                std::to_string(lines.size()));
  for (std::size_t i = 0; i < visible.size(); ++i)
    if (!visible[i].empty() && visible[i].size() != lines[i].size())
      throw Error("stylize/make_strokes: line " + std::to_string(i) + " has " + std::to_string(lines[i].size()) +
                  " points but " + std::to_string(visible[i].size()) + " visibility flags");

  StrokesResult result;
  result.depth_range = o.depth_range ? *o.depth_range : depth_range(lines, camera);
  std::vector<std::vector<Stroke>> per_line(lines.size());
  static const std::vector<std::uint8_t> kAllVisible;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lines.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      per_line[i] = line_strokes(lines[i], visible.empty() ? kAllVisible : visible[i], camera, result.depth_range, o);
  });
  for (std::uint32_t i = 0; i < per_line.size(); ++i)
    for (Stroke& s : per_line[i]) {
      result.strokes.push_back(std::move(s));
      result.line.push_back(i);
    }
  return result;
}

}  // namespace pcsketch::stylize
