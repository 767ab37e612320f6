#pragma once
// The uniform grid of the k-NN search (grid_knn.cpp) and of the tree's own-point queries (grid_queries.cpp): cells
// in a hash table by Morton code, and the candidates of a block of cells packed for a vectorised distance loop.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/ordered_key.h"
#include "grid_knn.h"
#include "morton.h"

namespace pcsketch::neighbourhood::detail {

using Cell = std::array<std::uint32_t, 3>;
using pcsketch::detail::key_index;
using pcsketch::detail::key_value;
using pcsketch::detail::ordered_key;

/// Inverse of spread_bits: the bits at every third place, packed.
inline std::uint32_t compact_bits(std::uint64_t v) {
  v &= 0x1249249249249249ULL;
  v = (v ^ (v >> 2)) & 0x10c30c30c30c30c3ULL;
  v = (v ^ (v >> 4)) & 0x100f00f00f00f00fULL;
  v = (v ^ (v >> 8)) & 0x1f0000ff0000ffULL;
  v = (v ^ (v >> 16)) & 0x1f00000000ffffULL;
  v = (v ^ (v >> 32)) & kMortonMax;
  return static_cast<std::uint32_t>(v);
}

/// A grid of cubes of edge `edge` anchored at `lo`; cell coordinates clamp to [0, kMortonMax] (NaN: 0).
struct Frame {
  Vec3d lo;
  double edge;
  Cell cell_of(const Vec3f& p) const {
    Cell c;
    for (int a = 0; a < 3; ++a) {
      const double t = (double(p[a]) - lo[a]) / edge;
      c[static_cast<std::size_t>(a)] =
          static_cast<std::uint32_t>(t >= 0 ? std::min(std::floor(t), double(kMortonMax)) : 0);
    }
    return c;
  }
  std::uint64_t code_of(const Vec3f& p) const {
    const Cell c = cell_of(p);
    return morton(c[0], c[1], c[2]);
  }
};

/// The occupied cells in order of first appearance (a cloud in spatial order visits them about in Morton order),
/// their runs of `order` and an open-addressing table from code to cell: grouped by counting, with no sort.
struct Grid {
  Frame frame;
  std::vector<std::uint32_t> order;  ///< point indices by cell, increasing within a cell
  std::vector<std::uint64_t> codes;  ///< per cell
  std::vector<std::uint32_t> start;  ///< per cell and one more: its run in `order`
  std::vector<std::uint32_t> slots;  ///< cell + 1, 0 = empty
  int shift = 64;

  Grid(const std::vector<Vec3f>& points, const Frame& f) : frame(f), start{0} {
    const std::size_t n = points.size();
    std::vector<std::uint64_t> point_code(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) point_code[i] = frame.code_of(points[i]);
    });
    resize_table(static_cast<int>(std::bit_width(n / 8 + 1)) + 1);
    std::vector<std::uint32_t> cell(n);
    for (std::size_t i = 0; i < n; ++i) {
      // Consecutive points of a cloud in spatial order mostly share a cell: the table is asked once per run.
      cell[i] = i > 0 && point_code[i] == point_code[i - 1] ? cell[i - 1] : insert(point_code[i]);
      ++start[cell[i] + 1];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    order.resize(n);
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < n; ++i) order[next[cell[i]]++] = i;
  }
  std::size_t slot(std::uint64_t code) const { return (code * 0x9E3779B97F4A7C15ULL) >> shift; }
  /// The cell with this code, or -1.
  std::int64_t find(std::uint64_t code) const {
    for (std::size_t s = slot(code);; s = (s + 1) & (slots.size() - 1)) {
      if (slots[s] == 0) return -1;
      if (codes[slots[s] - 1] == code) return slots[s] - 1;
    }
  }
  std::size_t cells() const { return codes.size(); }
  /// Starts loading the table slot of `code` (a hint: no effect on the result).
  void prefetch(std::uint64_t code) const { __builtin_prefetch(&slots[slot(code)]); }

 private:
  /// The cell of `code`, added (with a zero count in start) if new; the table doubles at half full.
  std::uint32_t insert(std::uint64_t code) {
    std::size_t s = slot(code);
    for (; slots[s] != 0; s = (s + 1) & (slots.size() - 1))
      if (codes[slots[s] - 1] == code) return slots[s] - 1;
    const auto cell = static_cast<std::uint32_t>(codes.size());
    codes.push_back(code);
    start.push_back(0);
    slots[s] = cell + 1;
    if (2 * codes.size() > slots.size()) resize_table(static_cast<int>(std::bit_width(slots.size())));
    return cell;
  }
  /// A table of 2^bits slots holding the cells so far.
  void resize_table(int bits) {
    shift = 64 - bits;
    slots.assign(std::size_t{1} << bits, 0);
    for (std::uint32_t cell = 0; cell < codes.size(); ++cell) {
      std::size_t s = slot(codes[cell]);
      while (slots[s] != 0) s = (s + 1) & (slots.size() - 1);
      slots[s] = cell + 1;
    }
  }
};

/// As nanoflann's L2_Simple_Adaptor, so that distances and ties come out the same: query minus point, summed over
/// x, y, z in this order in float.
inline float squared(float dx, float dy, float dz) {
  float d = dx * dx;
  d += dy * dy;
  d += dz * dz;
  return d;
}

/// The 27 cell offsets, nearest first (the cell itself, faces, edges, corners): near candidates come first and fill
/// the k best early, so that later ones mostly fail the first compare.
constexpr std::array<std::array<int, 3>, 27> kAround = [] {
  std::array<std::array<int, 3>, 27> out{};
  std::size_t m = 0;
  for (int ring = 0; ring <= 3; ++ring)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx * dx + dy * dy + dz * dz == ring) out[m++] = {dx, dy, dz};
  return out;
}();

/// The points of the 27 cells around one cell, as packed coordinates and indices.
struct Candidates {
  Cell centre;  ///< the cell whose points ask
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> index;
  std::vector<float> d2;            ///< per query: squared distances
  std::vector<std::uint64_t> keys;  ///< per query: the k best (squared distance bits, index); one compare orders them

  void gather(const Grid& grid, const std::vector<Vec3f>& points, std::size_t cell) {
    const std::uint64_t code = grid.codes[cell];
    centre = {compact_bits(code), compact_bits(code >> 1), compact_bits(code >> 2)};
    const Cell& c = centre;
    // The codes around first, their table slots fetched together: one at a time, each lookup waits on a cache miss.
    std::array<std::uint64_t, 27> around;
    std::size_t count = 0;
    for (const auto& [dx, dy, dz] : kAround) {
      const std::int64_t cx = std::int64_t(c[0]) + dx, cy = std::int64_t(c[1]) + dy, cz = std::int64_t(c[2]) + dz;
      if (std::min({cx, cy, cz}) < 0 || std::max({cx, cy, cz}) > kMortonMax) continue;
      around[count] = morton(std::uint32_t(cx), std::uint32_t(cy), std::uint32_t(cz));
      grid.prefetch(around[count++]);
    }
    take(grid, points, std::span(around.data(), count));
  }

  /// The points of the (2 reach + 1)³ cells around `cell`, for a row the 27 cells could not prove.
  void gather_wide(const Grid& grid, const std::vector<Vec3f>& points, const Cell& cell, int reach) {
    centre = cell;
    std::vector<std::uint64_t> around;
    for (int dz = -reach; dz <= reach; ++dz)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const std::int64_t cx = std::int64_t(cell[0]) + dx, cy = std::int64_t(cell[1]) + dy,
                             cz = std::int64_t(cell[2]) + dz;
          if (std::min({cx, cy, cz}) >= 0 && std::max({cx, cy, cz}) <= kMortonMax)
            around.push_back(morton(std::uint32_t(cx), std::uint32_t(cy), std::uint32_t(cz)));
        }
    take(grid, points, around);
  }

  /// The points of the cells of these codes (absent cells skipped), in this order.
  void take(const Grid& grid, const std::vector<Vec3f>& points, std::span<const std::uint64_t> codes) {
    x.clear(), y.clear(), z.clear(), index.clear();
    for (const std::uint64_t code : codes) {
      const std::int64_t other = grid.find(code);
      if (other < 0) continue;
      for (std::uint32_t r = grid.start[std::size_t(other)]; r < grid.start[std::size_t(other) + 1]; ++r) {
        const Vec3f& p = points[grid.order[r]];
        x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
        index.push_back(grid.order[r]);
      }
    }
  }

  /// The squared distances from q to every candidate, in a loop the compiler vectorises.
  void measure(const Vec3f& q) {
    const std::size_t count = index.size();
    d2.resize(count);
    for (std::size_t c = 0; c < count; ++c) {
      const float dx = q.x() - x[c], dy = q.y() - y[c], dz = q.z() - z[c];
      d2[c] = squared(dx, dy, dz);
    }
  }

  /// The k nearest candidates to point i (self excluded) by measure()'s distances into keys[0, k), sorted; false if
  /// fewer than k lie within `bound` (a squared distance, infinity if unknown). Then no candidate beyond the bound can
  /// be among the k nearest, whatever the bound was: only those within it (a few more than k with a close guess)
  /// compete, by insertion.
  bool nearest(std::uint32_t i, std::size_t k, float bound) {
    const std::size_t count = index.size();
    keys.resize(count + 1);
    std::size_t within = 0;
    for (std::size_t c = 0; c < count; ++c) {
      keys[within] = ordered_key(d2[c], index[c]);
      within += d2[c] <= bound && index[c] != i;
    }
    if (within < k) return false;
    // Insertion into the sorted first k: survivors are few, and near ones come first (kAround's order).
    for (std::size_t c = 1; c < within; ++c) {
      const std::uint64_t key = keys[c];
      if (c >= k && key >= keys[k - 1]) continue;
      std::size_t m = std::min(c, k - 1);
      for (; m > 0 && key < keys[m - 1]; --m) keys[m] = keys[m - 1];
      keys[m] = key;
    }
    return true;
  }
};

/// Distance from q to the outside of the (2 reach + 1)³ cells around `cell`: any point beyond is at least this far.
inline double way_out(const Frame& frame, const Vec3f& q, const Cell& cell, int reach = 1) {
  double d = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const double low = frame.lo[a] + (double(cell[static_cast<std::size_t>(a)]) - reach) * frame.edge;
    const double high = frame.lo[a] + (double(cell[static_cast<std::size_t>(a)]) + reach + 1.0) * frame.edge;
    d = std::min({d, double(q[a]) - low, high - double(q[a])});
  }
  return d;
}

/// A grid over a cloud's points (none when their box is empty, flat to a point or not finite).
struct GridKnn::Impl {
  const std::vector<Vec3f>& points;
  std::optional<Grid> grid;
  std::size_t most;  ///< candidates of 27 cells beyond which a row is the tree's (crowded copies: quadratic rows)
  double per_cell;   ///< points an occupied cell holds on average, about
  mutable std::atomic<std::uint32_t> misses{0};  ///< single-point queries the grid could not prove

  // A constructor, not an aggregate: clang 14 (the fuzz build) has no parenthesised aggregate initialisation.
  Impl(const std::vector<Vec3f>& p, std::size_t most_candidates, double points_per_cell)
      : points(p), most(most_candidates), per_cell(points_per_cell) {}

  /// The k nearest of point i (self excluded) into cand.keys from the (2 reach + 1)³ cells around its own, when the
  /// k-th is provably nearer than the way out of them.
  bool prove(Candidates& cand, std::size_t i, std::size_t k, int reach) const {
    cand.gather_wide(*grid, points, grid->frame.cell_of(points[i]), reach);
    if (cand.index.size() > std::size_t(reach * reach * reach) * most) return false;
    cand.measure(points[i]);
    if (!cand.nearest(static_cast<std::uint32_t>(i), k, INFINITY)) return false;
    // A margin far above float rounding: a point outside the cells can neither be nearer nor tie.
    const float kth = std::sqrt(key_value(cand.keys[k - 1]));
    return double(kth) < way_out(grid->frame, points[i], cand.centre, reach) * (1 - 1e-5);
  }
};

}  // namespace pcsketch::neighbourhood::detail
