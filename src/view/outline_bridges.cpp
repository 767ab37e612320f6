#include "outline_bridges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <unordered_map>

#include "point_grid.h"

namespace pcsketch::view::detail {
namespace {

/// A roll gives up after this many points: the far side of a cloud is never a gap worth bridging.
constexpr std::size_t kMaxSteps = 2000;
/// A bridge may be at most this many times as long as the straight gap it closes (plus one disc diameter).
constexpr float kDetour = 1.2f;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

float cross(const Vec2f& a, const Vec2f& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The projected points a disc can roll on (in front of the eye, finite), with a grid over them.
struct Rollable {
  std::vector<std::uint32_t> ids;  ///< cloud index of each rollable point
  std::vector<Vec2f> pts;          ///< its image position
  std::vector<float> radius;       ///< its disc radius, pixels
  float factor;                    ///< the disc radius in spacing units
  PointGrid<2> grid;

  static Rollable make(const ContourPoints& cp, float factor) {
    std::vector<std::uint32_t> ids;
    std::vector<Vec2f> pts;
    std::vector<float> radius;
    double sum = 0;
    for (std::uint32_t i = 0; i < cp.projected.size(); ++i)
      if (cp.spacing_px[i] > 0 && cp.projected[i].head<2>().allFinite()) {
        ids.push_back(i);
        pts.push_back(cp.projected[i].head<2>());
        radius.push_back(factor * cp.spacing_px[i]);
        sum += radius.back();
      }
    const float cell = ids.empty() ? 1.f : static_cast<float>(2 * sum / static_cast<double>(ids.size()));
    PointGrid<2> grid(pts, cell);
    return {std::move(ids), std::move(pts), std::move(radius), factor, std::move(grid)};
  }

  /// The next point a disc of radius `r` touches as it pivots around point `p` (rollable index) from centre
  /// `centre`, turning by `sense` (+1 / −1), and the disc's centre there; none when no point lies within 2r.
  std::optional<std::pair<std::uint32_t, Vec2f>> pivot(std::uint32_t p, std::uint32_t previous, const Vec2f& centre,
                                                        float r, float sense) const {
    const Vec2f P = pts[p];
    const Vec2f u0 = (centre - P).normalized();
    float best = std::numeric_limits<float>::infinity();
    std::optional<std::pair<std::uint32_t, Vec2f>> next;
    grid.for_each_within(P, 2 * r, [&](std::uint32_t q, float d2) {
      if (q == p || q == previous || d2 <= 0) return;
      const Vec2f d = pts[q] - P;
      const float length = std::sqrt(d2);
      const Vec2f mid = P + 0.5f * d;
      const Vec2f across = Vec2f(-d.y(), d.x()) / length;
      const float height = std::sqrt(std::max(0.f, r * r - 0.25f * d2));
      for (const float s : {-1.f, 1.f}) {
        const Vec2f c = mid + s * height * across;
        const Vec2f u = (c - P) / r;
        float angle = std::atan2(sense * cross(u0, u), u0.dot(u));
        if (angle < 0) angle += 2 * std::numbers::pi_v<float>;
        if (angle < 1e-5f || angle > best || (angle == best && next && q > next->first)) continue;
        best = angle;
        next = std::pair{q, c};
      }
    });
    return next;
  }
};

/// Where each outline vertex sits: its line and place, by rollable index.
struct Owner {
  std::uint32_t line = kNone;
  std::uint32_t place = 0;
};

float image_length(const Rollable& r, const std::vector<std::uint32_t>& chain) {
  float length = 0;
  for (std::size_t i = 1; i < chain.size(); ++i) length += (r.pts[chain[i]] - r.pts[chain[i - 1]]).norm();
  return length;
}

/// The traced outline seen from the rollable points: its lines and a grid over their vertices.
struct Traced {
  std::vector<std::vector<std::uint32_t>> lines;  ///< rollable indices of each line's vertices
  std::vector<float> lengths;                     ///< image length of each line
  std::vector<std::uint32_t> vertex;              ///< rollable index of each grid entry
  PointGrid<2> grid;

  /// `owner` (by rollable index) receives each traced vertex's line and place; the bridges add theirs later.
  static Traced make(const Rollable& r, const std::vector<std::uint32_t>& slot, const std::vector<Polyline>& outline,
                     std::vector<Owner>& owner) {
    std::vector<std::vector<std::uint32_t>> lines(outline.size());
    std::vector<float> lengths(outline.size());
    owner.assign(r.ids.size(), Owner{});
    std::vector<std::uint32_t> vertex;
    std::vector<Vec2f> pts;
    for (std::uint32_t l = 0; l < outline.size(); ++l) {
      for (const std::uint32_t i : outline[l].point_index)
        if (slot[i] != kNone) lines[l].push_back(slot[i]);
      for (std::uint32_t v = 0; v < lines[l].size(); ++v) {
        owner[lines[l][v]] = {l, v};
        vertex.push_back(lines[l][v]);
        pts.push_back(r.pts[lines[l][v]]);
      }
      lengths[l] = image_length(r, lines[l]);
    }
    PointGrid<2> grid(pts, r.grid.cell());
    return {std::move(lines), std::move(lengths), std::move(vertex), std::move(grid)};
  }
};

/// One roll from an open end of a traced line.
struct Roll {
  const Rollable& r;
  const Traced& traced;
  std::uint32_t line;
  bool at_back;
  float radius;          ///< the disc's, pixels: one for the whole roll (a disc that changed size between pivots
                         ///< would no longer touch the last point)
  std::size_t own_skip;  ///< own vertices from the end that do not count as met: those within 2 radii of it

  Roll(const Rollable& rollable, const Traced& t, std::uint32_t l, bool back)
      : r(rollable), traced(t), line(l), at_back(back) {
    const std::vector<std::uint32_t>& v = traced.lines[line];
    radius = r.radius[end()];
    float walked = 0;
    own_skip = 1;
    while (own_skip < v.size() && walked <= 2 * radius) {
      walked += (r.pts[at(own_skip)] - r.pts[at(own_skip - 1)]).norm();
      ++own_skip;
    }
  }
  /// The k-th vertex of the line counted from the rolling end.
  std::uint32_t at(std::size_t k) const {
    const std::vector<std::uint32_t>& v = traced.lines[line];
    return at_back ? v[v.size() - 1 - k] : v[k];
  }
  std::uint32_t end() const { return at(0); }

  /// Whether outline vertex k (rollable index) ends the roll.
  bool counts(std::uint32_t k, const std::vector<Owner>& owner) const {
    const Owner& o = owner[k];
    if (o.line == kNone) return false;
    if (o.line != line) return true;
    const std::size_t n = traced.lines[line].size();
    return (at_back ? n - 1 - o.place : o.place) >= own_skip;
  }

  /// The outline vertex the roll meets at point q: q itself, or the nearest traced vertex within a spacing of it
  /// (the traced line may run a point inside the outermost ones); kNone when none.
  std::uint32_t meets(std::uint32_t q, const std::vector<Owner>& owner) const {
    if (counts(q, owner)) return q;
    std::uint32_t best = kNone;
    float best_d2 = std::numeric_limits<float>::infinity();
    traced.grid.for_each_within(r.pts[q], radius / r.factor, [&](std::uint32_t j, float d2) {
      const std::uint32_t k = traced.vertex[j];
      if (d2 < best_d2 && counts(k, owner)) best = k, best_d2 = d2;
    });
    return best;
  }

  /// The rollable points of the bridge, the end first and the outline vertex it met last; empty when it met none.
  std::vector<std::uint32_t> run(const Vec2f& outward, const std::vector<Owner>& owner,
                                 std::vector<std::uint32_t>& stamp, std::uint32_t walk) const {
    const Vec2f heading = r.pts[end()] - r.pts[at(1)];
    const float sense = cross(outward, heading) > 0 ? 1.f : -1.f;  // turn from the empty side towards the heading
    std::vector<std::uint32_t> chain{end()};
    Vec2f centre = r.pts[end()] + radius * outward;
    std::uint32_t previous = at(1);
    while (chain.size() < kMaxSteps) {
      const auto next = r.pivot(chain.back(), previous, centre, radius, sense);
      if (!next || stamp[next->first] == walk) return {};  // a dead end, or circling
      const auto [q, c] = *next;
      stamp[q] = walk;
      previous = chain.back();
      chain.push_back(q);
      centre = c;
      const std::uint32_t met = meets(q, owner);
      if (met == kNone) continue;
      if (met != q) chain.push_back(met);
      return chain;
    }
    return {};
  }
};

std::vector<Polyline> find_bridges(const ContourPoints& cp, const std::vector<Vec3f>& positions,
                                   const std::vector<Polyline>& outline, const ContourOptions& o) {
  const Rollable r = Rollable::make(cp, o.bridge_radius_factor);
  std::vector<std::uint32_t> slot(cp.projected.size(), kNone);  // cloud index → rollable index
  for (std::uint32_t k = 0; k < r.ids.size(); ++k) slot[r.ids[k]] = k;
  std::vector<Owner> owner;
  const Traced traced = Traced::make(r, slot, outline, owner);
  const auto outward_of = [&](std::uint32_t k) {
    const auto it = std::lower_bound(cp.boundary.begin(), cp.boundary.end(), r.ids[k]);
    return it != cp.boundary.end() && *it == r.ids[k] ? cp.outward[static_cast<std::size_t>(it - cp.boundary.begin())]
                                                     : Vec2f::Zero().eval();
  };
  std::vector<std::uint32_t> stamp(r.ids.size(), 0);
  std::uint32_t walk = 0;
  const auto bridge_line = static_cast<std::uint32_t>(outline.size());  // the owner of bridge vertices
  std::vector<Polyline> bridges;
  for (std::uint32_t l = 0; l < outline.size(); ++l) {
    if (outline[l].closed || traced.lines[l].size() < 2) continue;
    for (const bool at_back : {false, true}) {
      const Roll roll(r, traced, l, at_back);
      if (owner[roll.end()].line == bridge_line) continue;  // an earlier bridge ended here
      const Vec2f outward = outward_of(roll.end());
      if (outward.squaredNorm() == 0) continue;
      const std::vector<std::uint32_t> chain = roll.run(outward, owner, stamp, ++walk);
      if (chain.size() < 2) continue;
      const std::uint32_t met = owner[chain.back()].line;
      const float longer = std::max(traced.lengths[l], met < outline.size() ? traced.lengths[met] : 0.f);
      // A roll much longer than the gap it closes went into the cloud (a sparse patch wider than the disc).
      const float chord = (r.pts[chain.back()] - r.pts[chain.front()]).norm();
      const float walked = image_length(r, chain);
      if (walked > longer || walked > kDetour * chord + 2 * roll.radius) continue;
      Polyline line;
      for (const std::uint32_t k : chain) {
        line.points.push_back(positions[r.ids[k]]);
        line.point_index.push_back(r.ids[k]);
      }
      for (std::size_t v = 1; v + 1 < chain.size(); ++v) owner[chain[v]] = {bridge_line, 0};
      owner[chain.front()].line = owner[chain.back()].line = bridge_line;  // both ends are joined now
      bridges.push_back(std::move(line));
    }
  }
  return bridges;
}

/// Drops the last vertex of an outline line (vertices and point_index only: it has no curvature).
void drop_last(Polyline& line) {
  line.points.pop_back();
  line.point_index.pop_back();
}

/// Joins open lines that end at the same cloud point into one line (closed when it comes back to its start), so a
/// traced piece and its bridges are one stroke: fusion and the line finish then treat them as one.
std::vector<Polyline> join_at_ends(std::vector<Polyline> lines) {
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> ends;  // cloud point → open lines ending there
  for (std::size_t l = 0; l < lines.size(); ++l)
    if (!lines[l].closed && lines[l].point_index.size() >= 2) {
      ends[lines[l].point_index.front()].push_back(l);
      ends[lines[l].point_index.back()].push_back(l);
    }
  std::vector<char> taken(lines.size(), 0);
  std::vector<Polyline> out;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    if (taken[l]) continue;
    taken[l] = 1;
    Polyline line = std::move(lines[l]);
    for (int side = 0; side < 2 && !line.closed && line.point_index.size() >= 2; ++side) {
      for (;;) {
        const std::uint32_t end = line.point_index.back();
        const auto it = ends.find(end);
        if (it == ends.end()) break;
        const auto free = std::find_if(it->second.begin(), it->second.end(), [&](std::size_t m) { return !taken[m]; });
        if (free == it->second.end()) break;
        const std::size_t next = *free;
        taken[next] = 1;
        if (lines[next].point_index.back() == end) lines[next].reverse();
        drop_last(line);  // the vertex both lines share: `next` starts with it
        line.append(std::move(lines[next]));
        if (line.point_index.front() == line.point_index.back()) {  // back at its start
          drop_last(line);
          line.closed = true;
          break;
        }
      }
      line.reverse();  // the other end next
    }
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace

void bridge_outline(const ContourPoints& cp, const std::vector<Vec3f>& positions, std::vector<Polyline>& outline,
                    const ContourOptions& o) {
  const bool any_open = std::any_of(outline.begin(), outline.end(), [](const Polyline& l) { return !l.closed; });
  if (!(o.bridge_radius_factor > 0) || !any_open) return;
  std::vector<Polyline> bridges = find_bridges(cp, positions, outline, o);
  if (bridges.empty()) return;
  std::move(bridges.begin(), bridges.end(), std::back_inserter(outline));
  outline = join_at_ends(std::move(outline));
}

}  // namespace pcsketch::view::detail
