#include "pcsketch/stylize/fuse.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/angles.h"
#include "pcsketch/core/error.h"

namespace pcsketch::stylize {

namespace {

constexpr std::uint32_t kOwn = std::numeric_limits<std::uint32_t>::max();

/// Who draws a vertex: its own stroke (stroke == kOwn) or `stroke`, near that stroke's vertex `vertex`.
struct Match {
  std::uint32_t stroke = kOwn;
  std::uint32_t vertex = 0;
  float gap = 0.f;  ///< image distance to that stroke, px
};

/// The image segments of the strokes taking part, listed per grid cell: every cell a segment's bounding box touches.
/// Cells are as wide as the fusion distance, so the 3×3 cells around a point hold every segment within it.
class SegmentGrid {
 public:
  SegmentGrid(const std::vector<Stroke>& strokes, const std::vector<std::uint8_t>& takes_part, float cell)
      : cell_(cell) {
    for (std::uint32_t s = 0; s < strokes.size(); ++s) {
      if (!takes_part[s]) continue;
      const std::vector<Vec2f>& p = strokes[s].image_points;
      for (std::uint32_t k = 0; k < strokes[s].segments(); ++k) {
        const Vec2f& a = p[k];
        const Vec2f& b = p[(k + 1) % p.size()];
        for (std::int64_t y = cell_of(std::min(a.y(), b.y())); y <= cell_of(std::max(a.y(), b.y())); ++y)
          for (std::int64_t x = cell_of(std::min(a.x(), b.x())); x <= cell_of(std::max(a.x(), b.x())); ++x)
            entries_.push_back({key(x, y), {s, k}});
      }
    }
    std::sort(entries_.begin(), entries_.end());
  }

  /// Calls f(stroke, segment) for the segments listed in the 3×3 cells around `p` (a segment may come more than once).
  template <class F>
  void visit(const Vec2f& p, F&& f) const {
    const std::int64_t cx = cell_of(p.x()), cy = cell_of(p.y());
    for (std::int64_t y = cy - 1; y <= cy + 1; ++y)
      for (std::int64_t x = cx - 1; x <= cx + 1; ++x) {
        const Entry probe{key(x, y), {0, 0}};
        for (auto it = std::lower_bound(entries_.begin(), entries_.end(), probe);
             it != entries_.end() && it->first == probe.first; ++it)
          f(it->second.first, it->second.second);
      }
  }

 private:
  using Entry = std::pair<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>>;
  // Clamped so that a stray far-away point cannot overflow the key (image coordinates are finite here).
  std::int64_t cell_of(float v) const {
    return static_cast<std::int64_t>(std::clamp(std::floor(v / cell_), -1e9f, 1e9f));
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x + (1ll << 31)) << 32) | static_cast<std::uint64_t>(y + (1ll << 31));
  }
  float cell_;
  std::vector<Entry> entries_;
};

float distance_to_segment(const Vec2f& p, const Vec2f& a, const Vec2f& b) {
  const Vec2f ab = b - a;
  const float len2 = ab.squaredNorm();
  const float t = len2 > 0.f ? std::clamp((p - a).dot(ab) / len2, 0.f, 1.f) : 0.f;
  return (a + t * ab - p).norm();
}

/// Direction of a stroke at vertex i, between the points `arm` px of path before and after it (vertices, not
/// interpolated): a staircase's single steps do not turn it.
Vec2f tangent(const Stroke& s, std::size_t i, float arm) {
  const std::vector<Vec2f>& p = s.image_points;
  const std::size_t n = p.size();
  auto walk = [&](int step) {
    std::size_t j = i;
    float length = 0.f;
    for (std::size_t k = 0; k + 1 < n && length < arm; ++k) {
      const bool at_end = step > 0 ? j + 1 == n : j == 0;
      if (at_end && !s.closed) break;
      const std::size_t next = (j + n + static_cast<std::size_t>(step)) % n;
      length += (p[next] - p[j]).norm();
      j = next;
    }
    return p[j];
  };
  return walk(1) - walk(-1);
}

/// A maximal run of consecutive vertices drawn by the same stroke. Runs of a closed stroke wrap around.
struct Run {
  std::size_t first = 0, count = 0;
  bool has_next = false;  ///< the vertex after the run exists (the run's piece extends to it)
};

/// Runs of equal Match::stroke; a closed stroke with more than one run starts at a change, so no run wraps twice.
std::vector<Run> runs_of(const std::vector<Match>& m, bool closed) {
  const std::size_t n = m.size();
  std::size_t start = 0;
  if (closed)
    while (start < n && m[start].stroke == m[(start + n - 1) % n].stroke) ++start;
  if (start == n) return {Run{0, n, false}};  // one state all round
  std::vector<Run> runs;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (start + k) % n;
    if (k == 0 || m[i].stroke != m[(i + n - 1) % n].stroke) runs.push_back({i, 0, false});
    ++runs.back().count;
  }
  for (Run& r : runs) r.has_next = closed || r.first + r.count < n;
  return runs;
}

float run_length(const Stroke& s, const Run& r) {
  const std::size_t n = s.image_points.size();
  float length = 0.f;
  for (std::size_t k = 0; k + 1 < r.count + (r.has_next ? 1 : 0); ++k)
    length += (s.image_points[(r.first + k + 1) % n] - s.image_points[(r.first + k) % n]).norm();
  return length;
}

void assign(std::vector<Match>& m, const Run& r, const Match& value) {
  for (std::size_t k = 0; k < r.count; ++k) m[(r.first + k) % m.size()] = value;
}

/// Keeps only the stretches worth fusing: matched runs shorter than min_stretch_px are drawn after all, unless the run
/// is the whole stroke and lies within `tight` px of the other all along (never when `tight` < 0), and each kept run is
/// drawn by one stroke (the one most of its vertices matched). Own runs then join a fused neighbour when they are stubs
/// (under min_stretch_px: a stub left at the end of a stretch would be drawn as a tick) or short gaps between two
/// stretches fused into the same stroke (under max_gap_px: where two tracings hover about the fusion distance the line
/// drawn would otherwise switch between them).
void keep_stretches(const Stroke& s, std::vector<Match>& m, const FusionOptions& o, float tight) {
  const std::vector<Run> matched = runs_of(m, s.closed);
  // A stroke within `tight` of another over its whole length is a double however short (it cannot merely cross or
  // touch: the angle test holds at every vertex).
  const bool whole =
      matched.size() == 1 && std::all_of(m.begin(), m.end(), [tight](const Match& v) { return v.gap <= tight; });
  for (const Run& r : matched) {
    if (m[r.first].stroke == kOwn) continue;
    if (!whole && run_length(s, r) < o.min_stretch_px) {
      assign(m, r, {});
      continue;
    }
    std::map<std::uint32_t, std::size_t> votes;
    for (std::size_t k = 0; k < r.count; ++k) ++votes[m[(r.first + k) % m.size()].stroke];
    const std::uint32_t winner =
        std::max_element(votes.begin(), votes.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
    Match chosen;
    for (std::size_t k = 0; k < r.count && (chosen.stroke == kOwn || 2 * k <= r.count); ++k)
      if (m[(r.first + k) % m.size()].stroke == winner) chosen = m[(r.first + k) % m.size()];
    assign(m, r, chosen);
  }
  const std::vector<Run> runs = runs_of(m, s.closed);
  if (runs.size() < 2) return;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Run& r = runs[k];
    if (m[r.first].stroke != kOwn) continue;
    const bool has_before = s.closed || k > 0, has_after = s.closed || k + 1 < runs.size();
    const Match before = has_before ? m[runs[(k + runs.size() - 1) % runs.size()].first] : Match{};
    const Match after = has_after ? m[runs[(k + 1) % runs.size()].first] : Match{};
    const float length = run_length(s, r);
    const bool gap = has_before && has_after && before.stroke == after.stroke && length < o.max_gap_px;
    if (gap || length < o.min_stretch_px) assign(m, r, has_before ? before : after);
  }
}

/// Vertices `first` … `first + count − 1` (modulo #S) of `s` as a stroke of their own.
Stroke slice(const Stroke& s, std::size_t first, std::size_t count) {
  const std::size_t n = s.points.size();
  Stroke out;
  out.kind = s.kind;
  out.visible = s.visible;
  out.grey = s.grey;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = (first + k) % n;
    out.points.push_back(s.points[i]);
    out.image_points.push_back(s.image_points[i]);
    out.widths.push_back(s.widths[i]);
    if (k + 1 < count) {
      out.half_widths.push_back(s.half_widths[2 * i]);
      out.half_widths.push_back(s.half_widths[2 * i + 1]);
    }
  }
  return out;
}

/// For each vertex of stroke `s`, the drawn segment of an earlier stroke (in `position` order) it runs along.
std::vector<Match> matches(const std::vector<Stroke>& strokes, std::uint32_t s,
                           const std::vector<std::uint32_t>& position, const std::vector<std::vector<Match>>& drawn_by,
                           const SegmentGrid& grid, float distance, float cos_max) {
  const Stroke& stroke = strokes[s];
  std::vector<Match> m(stroke.image_points.size());
  for (std::size_t i = 0; i < m.size(); ++i) {
    const Vec2f& p = stroke.image_points[i];
    const Vec2f t = tangent(stroke, i, distance).normalized();
    float best = distance;
    grid.visit(p, [&](std::uint32_t w, std::uint32_t k) {
      if (position[w] >= position[s]) return;
      const std::vector<Vec2f>& q = strokes[w].image_points;
      const std::uint32_t k1 = static_cast<std::uint32_t>((k + 1) % q.size());
      if (drawn_by[w][k].stroke != kOwn || drawn_by[w][k1].stroke != kOwn) return;
      const float d = distance_to_segment(p, q[k], q[k1]);
      const Vec2f dir = (q[k1] - q[k]).normalized();
      if (!(d <= best) || !(std::abs(dir.dot(t)) >= cos_max)) return;
      best = d;
      m[i] = {w, (p - q[k]).squaredNorm() <= (p - q[k1]).squaredNorm() ? k : k1, d};
    });
  }
  return m;
}

bool finite(const std::vector<Vec2f>& points) {
  return std::all_of(points.begin(), points.end(), [](const Vec2f& p) { return p.allFinite(); });
}

}  // namespace

FusionResult fuse_strokes(std::vector<Stroke> strokes, const std::vector<FusionRank>& rank, float pen_width_px,
                          const FusionOptions& o) {
  if (rank.size() != strokes.size())
    throw Error("stylize/fuse: " + std::to_string(rank.size()) + " ranks for " + std::to_string(strokes.size()) +
                " strokes");
  FusionResult result;
  const float distance = o.distance_widths * pen_width_px;
  const std::size_t count = strokes.size();
  std::vector<std::uint8_t> takes_part(count, 0);
  std::vector<float> length(count, 0.f);
  std::vector<std::uint32_t> order;
  for (std::uint32_t s = 0; s < count; ++s) {
    const Stroke& st = strokes[s];
    takes_part[s] = o.enabled && distance > 0.f && rank[s] != FusionRank::None && st.visible &&
                    st.image_points.size() >= 2 && finite(st.image_points);
    if (!takes_part[s]) continue;
    length[s] = st.image_length();
    order.push_back(s);
  }
  // Drawn first: lower rank, then longer, then earlier.
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (rank[a] != rank[b]) return rank[a] < rank[b];
    if (length[a] != length[b]) return length[a] > length[b];
    return a < b;
  });
  std::vector<std::uint32_t> position(count, std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t p = 0; p < order.size(); ++p) position[order[p]] = p;

  std::vector<std::vector<Match>> drawn_by(count);
  for (std::uint32_t s = 0; s < count; ++s) drawn_by[s].resize(strokes[s].image_points.size());
  if (!order.empty()) {
    const SegmentGrid grid(strokes, takes_part, distance);
    const float cos_max = std::cos(o.max_angle_deg * pcsketch::detail::kDegToRad);
    // In drawing order: a stroke's own matches are final before any later stroke looks at them.
    for (const std::uint32_t s : order) {
      drawn_by[s] = matches(strokes, s, position, drawn_by, grid, distance, cos_max);
      // Contours within half a pen width: further off a short one may be a fold beside the outline (within a pen
      // width the 26 meshes' clean recall lost 0.003). Ridges and valleys keep the minimum stretch: those beside the
      // outline are the edges it runs along (a plate's rims), which their own layer should hold (docs/stylize.md).
      const float tight = rank[s] == FusionRank::Feature ? -1.f : 0.5f * pen_width_px;
      keep_stretches(strokes[s], drawn_by[s], o, tight);
    }
  }

  // Cut every stroke into its runs; a piece extends to the next run's first vertex so the pieces meet.
  std::vector<std::vector<std::pair<Run, std::uint32_t>>> pieces(count);  // (run, index in the output)
  for (std::uint32_t s = 0; s < count; ++s) {
    const std::vector<Run> runs = runs_of(drawn_by[s], strokes[s].closed);
    if (runs.size() == 1) {
      pieces[s].push_back({runs[0], static_cast<std::uint32_t>(result.strokes.size())});
      result.strokes.push_back(std::move(strokes[s]));
      continue;
    }
    for (const Run& r : runs) {
      pieces[s].push_back({r, static_cast<std::uint32_t>(result.strokes.size())});
      result.strokes.push_back(slice(strokes[s], r.first, r.count + (r.has_next ? 1 : 0)));
    }
  }
  for (std::uint32_t s = 0; s < count; ++s)
    for (const auto& [run, index] : pieces[s]) {
      const Match m = drawn_by[s][run.first];
      if (m.stroke == kOwn) continue;
      const std::size_t n = drawn_by[m.stroke].size();
      for (const auto& [winner_run, winner_index] : pieces[m.stroke])
        if (drawn_by[m.stroke][winner_run.first].stroke == kOwn &&
            (m.vertex + n - winner_run.first) % n < winner_run.count)
          result.strokes[index].fused_into = winner_index;
      ++result.fused_stretches;
    }
  return result;
}

}  // namespace pcsketch::stylize
