#include "stroke_ops.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace pcsketch::plotter::detail {

double image_length(const Stroke& s) {
  const std::vector<Vec2f>& q = s.image_points;
  double length = 0;
  for (std::size_t i = 1; i < q.size(); ++i) length += (q[i] - q[i - 1]).cast<double>().norm();
  if (s.closed && q.size() > 2) length += (q.front() - q.back()).cast<double>().norm();
  return length;
}

Vec2d first_point(const Stroke& s) { return s.image_points.front().cast<double>(); }

Vec2d last_point(const Stroke& s) { return (s.closed ? s.image_points.front() : s.image_points.back()).cast<double>(); }

void reverse(Stroke& s) {
  std::reverse(s.points.begin(), s.points.end());
  std::reverse(s.image_points.begin(), s.image_points.end());
  std::reverse(s.widths.begin(), s.widths.end());
  // Segment i's halves (2i, 2i + 1) become the reversed segment's (2i + 1, 2i): reversing the array does both.
  std::reverse(s.half_widths.begin(), s.half_widths.end());
}

namespace {

/// Per-vertex array `a` of a stroke with `na` vertices, concatenated with `b` of `nb`; cleared unless both are.
template <class T>
void concatenate(std::vector<T>& a, std::size_t na, const std::vector<T>& b, std::size_t nb, std::size_t skip) {
  if (a.size() != na || b.size() != nb) {
    a.clear();
    return;
  }
  a.insert(a.end(), b.begin() + static_cast<std::ptrdiff_t>(skip), b.end());
}

}  // namespace

void append(Stroke& into, const Stroke& next) {
  const std::size_t na = into.image_points.size(), nb = next.image_points.size();
  // A shared vertex is dropped, so no zero-length segment (a dot under a round cap) is drawn.
  const std::size_t skip = into.image_points.back() == next.image_points.front() ? 1 : 0;
  const bool halves =
      na >= 2 && nb >= 2 && into.half_widths.size() == 2 * (na - 1) && next.half_widths.size() == 2 * (nb - 1);
  if (halves) {
    if (skip == 0) {
      into.half_widths.push_back(into.half_widths.back());  // the connecting segment
      into.half_widths.push_back(next.half_widths.front());
    }
    into.half_widths.insert(into.half_widths.end(), next.half_widths.begin(), next.half_widths.end());
  } else {
    into.half_widths.clear();
  }
  concatenate(into.points, na, next.points, nb, skip);
  concatenate(into.widths, na, next.widths, nb, skip);
  into.image_points.insert(into.image_points.end(), next.image_points.begin() + static_cast<std::ptrdiff_t>(skip),
                           next.image_points.end());
}

namespace {

/// A straight hatch stroke as a piece of the line {x : normal·x = offset}, from t0 to t1 along its direction.
struct Piece {
  double angle = 0;   ///< direction, radians in [0, π)
  double offset = 0;  ///< signed distance of the line from the image origin, pixels
  double t0 = 0, t1 = 0;
  std::size_t stroke = 0;
};

bool straight_piece(const Stroke& s, double tolerance, std::size_t index, Piece& piece) {
  if (s.kind != LineKind::Hatch || s.closed || s.image_points.size() < 2) return false;
  const Vec2d a = first_point(s), b = s.image_points.back().cast<double>();
  const double length = (b - a).norm();
  if (!(length > tolerance)) return false;
  Vec2d dir = (b - a) / length;
  if (dir.y() < 0 || (dir.y() == 0 && dir.x() < 0)) dir = -dir;  // one direction per line: angle in [0, π)
  const Vec2d normal(-dir.y(), dir.x());
  for (const Vec2f& p : s.image_points)
    if (std::abs(normal.dot(p.cast<double>() - a)) > tolerance) return false;
  piece = {std::atan2(dir.y(), dir.x()), normal.dot(a), std::min(dir.dot(a), dir.dot(b)),
           std::max(dir.dot(a), dir.dot(b)), index};
  return true;
}

/// Runs [begin, end) of `items` (sorted by key) in which consecutive keys differ by at most `gap`.
template <class Key>
std::vector<std::pair<std::size_t, std::size_t>> clusters(const std::vector<Piece>& items, Key key, double gap) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= items.size(); ++i)
    if (i == items.size() || key(items[i]) - key(items[i - 1]) > gap) {
      runs.emplace_back(begin, i);
      begin = i;
    }
  return runs;
}

std::vector<Piece> slice(const std::vector<Piece>& items, std::pair<std::size_t, std::size_t> run) {
  return {items.begin() + static_cast<std::ptrdiff_t>(run.first),
          items.begin() + static_cast<std::ptrdiff_t>(run.second)};
}

/// One stroke along the line of `lo` from lo.t0 to hi.t1: the stroke whose end reaches t0 gives its start, the one
/// reaching t1 its end (3D points included), the first gives kind, grey and width.
Stroke span_stroke(const std::vector<Stroke>& strokes, const Piece& lo, const Piece& hi) {
  const Vec2d dir(std::cos(lo.angle), std::sin(lo.angle));
  auto end_at = [&](const Piece& p, double t, Vec2f& image, Vec3f& point, bool& has_point) {
    const Stroke& s = strokes[p.stroke];
    const bool at_front =
        std::abs(dir.dot(first_point(s)) - t) <= std::abs(dir.dot(s.image_points.back().cast<double>()) - t);
    image = at_front ? s.image_points.front() : s.image_points.back();
    has_point = has_point && s.points.size() == s.image_points.size();
    if (has_point) point = at_front ? s.points.front() : s.points.back();
  };
  Stroke out = strokes[lo.stroke];
  Vec2f a, b;
  Vec3f pa = Vec3f::Zero(), pb = Vec3f::Zero();
  bool has_points = true;
  end_at(lo, lo.t0, a, pa, has_points);
  end_at(hi, hi.t1, b, pb, has_points);
  out.image_points = {a, b};
  out.points = has_points ? std::vector<Vec3f>{pa, pb} : std::vector<Vec3f>{};
  const float width = out.widths.empty() ? 0.f : out.widths.front();
  out.widths = out.widths.empty() ? std::vector<float>{} : std::vector<float>{width, width};
  out.half_widths = out.widths.empty() ? std::vector<float>{} : std::vector<float>{width, width};
  return out;
}

/// The pieces of one line: one stroke per stretch where they overlap (or nearly meet); a piece alone stays as it was.
void union_on_line(std::vector<Piece> line, std::vector<Stroke>& strokes, double tolerance, std::vector<Stroke>& out,
                   double& removed_px) {
  std::sort(line.begin(), line.end(),
            [](const Piece& x, const Piece& y) { return std::tie(x.t0, x.stroke) < std::tie(y.t0, y.stroke); });
  std::size_t first = 0;
  Piece reach = line[0];  // the piece reaching farthest along the line so far
  double drawn = 0;       // length of the stretch's pieces, overlaps counted each time
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i < line.size() && (i == first || line[i].t0 <= reach.t1 + tolerance)) {
      if (line[i].t1 > reach.t1) reach = line[i];
      drawn += line[i].t1 - line[i].t0;
      continue;
    }
    if (i == first + 1) {
      out.push_back(std::move(strokes[line[first].stroke]));
    } else {
      out.push_back(span_stroke(strokes, line[first], reach));
      removed_px += std::max(0.0, drawn - (reach.t1 - line[first].t0));
    }
    if (i == line.size()) break;
    first = i;
    reach = line[i];
    drawn = line[i].t1 - line[i].t0;
  }
}

}  // namespace

std::vector<Stroke> merge_collinear(std::vector<Stroke> strokes, double tolerance, double& removed_px) {
  std::vector<Piece> pieces;
  std::vector<Stroke> out;
  for (std::size_t i = 0; i < strokes.size(); ++i) {
    Piece piece;
    if (straight_piece(strokes[i], tolerance, i, piece))
      pieces.push_back(piece);
    else
      out.push_back(std::move(strokes[i]));
  }
  // Directions within tolerance over the image's size are one direction; lines of the wrap-around (angle near 0 and
  // near π) are not joined, which leaves near-horizontal duplicates drawn twice.
  double extent = 1;
  for (const Piece& p : pieces) extent = std::max({extent, std::abs(p.t0), std::abs(p.t1), std::abs(p.offset)});
  std::sort(pieces.begin(), pieces.end(),
            [](const Piece& a, const Piece& b) { return std::tie(a.angle, a.stroke) < std::tie(b.angle, b.stroke); });
  for (const auto& angle_run : clusters(
           pieces, [](const Piece& p) { return p.angle; }, tolerance / extent)) {
    std::vector<Piece> same_angle = slice(pieces, angle_run);
    std::sort(same_angle.begin(), same_angle.end(), [](const Piece& a, const Piece& b) {
      return std::tie(a.offset, a.stroke) < std::tie(b.offset, b.stroke);
    });
    for (const auto& line_run : clusters(
             same_angle, [](const Piece& p) { return p.offset; }, tolerance))
      union_on_line(slice(same_angle, line_run), strokes, tolerance, out, removed_px);
  }
  return out;
}

}  // namespace pcsketch::plotter::detail
