#include "pcsketch/neighbourhood/neighbourhoods.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "neighbourhood/parallel_chunks.h"
#include "pcsketch/core/error.h"

namespace pcsketch::neighbourhood {

namespace {

/// Largest k the grid search serves (the shared neighbourhood has 16); larger ones are left to the kd-tree.
constexpr std::size_t kGridMaxK = 32;
/// Below this many points the kd-tree alone is as fast as building a grid.
constexpr std::size_t kGridMinPoints = 4096;
/// Points whose k-th neighbour distance is estimated to set the cell size, and the points on either side of each
/// (in index order) the estimate looks at.
constexpr std::size_t kCellSamples = 256, kWindow = 64;
/// Cell size: the typical k-th neighbour distance times this, measured fastest on the bunny's uneven vertices: the
/// 3×3×3 block certifies ~90% of the lists, the 5×5×5 nearly all the others.
constexpr double kCellFactor = 1.25;
/// Cells per axis of a 64-bit cell key (21 bits each).
constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;
/// A 3×3×3 block of more candidates than this times k (cells enlarged to bound the key range, dense clusters) is
/// left to the kd-tree, which keeps the grid's cost linear; larger blocks may hold more in proportion to their area.
constexpr std::size_t kMaxCandidatesPerK = 32;
/// Blocks grow to (2·kMaxShell+1)³ cells for the points whose k-th neighbour lies beyond the 3×3×3 block.
constexpr std::int64_t kMaxShell = 3;
/// Above this many close candidates per k, ranking them pairwise costs more than sorting.
constexpr std::size_t kRankMaxPerK = 4;
/// The first, tighter selection bound: the previous point's k-th squared distance times this (1.22 in distance).
constexpr float kPreviousBoundFactor = 1.5f;

/// The k-NN of `i` from the kd-tree, written to its slots of `result`.
void tree_neighbours(const KdTree& tree, std::size_t i, Neighbourhoods& result) {
  thread_local std::vector<std::uint32_t> found;
  thread_local std::vector<float> found_distances;
  tree.knn_of_point(i, result.k, found, found_distances);
  std::copy(found.begin(), found.end(), result.indices.begin() + i * result.k);
  std::copy(found_distances.begin(), found_distances.end(), result.distances.begin() + i * result.k);
}

/// Squared distance summed exactly as nanoflann's L2_Simple_Adaptor does (x, then y, then z, in float), so that the
/// grid and the kd-tree rank every candidate alike.
inline float squared_distance(float qx, float qy, float qz, float px, float py, float pz) {
  const float dx = qx - px, dy = qy - py, dz = qz - pz;
  float d = dx * dx;
  d += dy * dy;
  d += dz * dz;
  return d;
}

/// (squared distance bits, index): for non-negative floats the bits order like the values, so one integer compare
/// ranks by distance, then index.
inline std::uint64_t rank_key(float squared, std::uint32_t index) {
  return static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(squared)) << 32 | index;
}

/// Points sorted by uniform grid cell, with the cell size and the run of each occupied cell.
struct Grid {
  Vec3d lo;
  double cell = 0;
  std::vector<float> xs, ys, zs;       ///< positions in cell order
  std::vector<std::uint32_t> ids;      ///< point index in cell order
  std::vector<std::uint64_t> keys;     ///< occupied cells' keys, ascending
  std::vector<std::uint32_t> starts;   ///< first position of each occupied cell, then the point count

  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::uint64_t>(x) << 42 | static_cast<std::uint64_t>(y) << 21 | static_cast<std::uint64_t>(z);
  }
  std::int64_t coordinate(float p, int axis) const {
    return static_cast<std::int64_t>(std::floor((static_cast<double>(p) - lo[axis]) / cell));
  }
  /// Position of the first point whose cell key is ≥ k.
  std::uint32_t first_at(std::uint64_t k) const {
    return starts[static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), k) - keys.begin())];
  }
};

/// Sorts the points into cells of size `cell` over their bounding box `box`.
Grid make_grid(const std::vector<Vec3f>& points, const Box3f& box, double cell) {
  Grid grid;
  grid.lo = box.min.cast<double>();
  grid.cell = cell;
  struct Keyed {
    std::uint64_t key;
    std::uint32_t index;
    bool operator<(const Keyed& o) const { return key < o.key || (key == o.key && index < o.index); }
  };
  const std::size_t n = points.size();
  std::vector<Keyed> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const Vec3f& p = points[i];
      keyed[i] = {Grid::key(grid.coordinate(p.x(), 0), grid.coordinate(p.y(), 1), grid.coordinate(p.z(), 2)),
                  static_cast<std::uint32_t>(i)};
    }
  });
  // Keys are unique with the index as tie-break, so the parallel sort is deterministic.
  tbb::parallel_sort(keyed.begin(), keyed.end());
  grid.xs.resize(n), grid.ys.resize(n), grid.zs.resize(n), grid.ids.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Vec3f& p = points[keyed[j].index];
    grid.xs[j] = p.x(), grid.ys[j] = p.y(), grid.zs[j] = p.z();
    grid.ids[j] = keyed[j].index;
    if (j == 0 || keyed[j].key != keyed[j - 1].key) {
      grid.keys.push_back(keyed[j].key);
      grid.starts.push_back(static_cast<std::uint32_t>(j));
    }
  }
  grid.starts.push_back(static_cast<std::uint32_t>(n));
  return grid;
}

/// A typical k-th neighbour distance without a kd-tree: at points spread evenly along the (spatially sorted) cloud,
/// the k-th smallest distance to the kWindow points on either side in index order. That overestimates the true
/// k-th distance where the curve jumps, so its median is used: it came within 0–20% of the true distances' 85th
/// percentile on the shared models and on uniform samples. An unsorted cloud gives large cells, whose blocks are
/// then overfull and go to the kd-tree: slower, still exact.
double typical_kth_distance(const std::vector<Vec3f>& points, std::size_t k) {
  const std::size_t n = points.size();
  std::vector<float> kth(kCellSamples);
  tbb::parallel_for(std::size_t{0}, kCellSamples, [&](std::size_t s) {
    const std::size_t i = s * n / kCellSamples;
    std::vector<float> window;
    for (std::size_t j = i > kWindow ? i - kWindow : 0; j < std::min(n, i + kWindow + 1); ++j)
      if (j != i) window.push_back((points[j] - points[i]).squaredNorm());
    const auto at = window.begin() + static_cast<std::ptrdiff_t>(std::min(k, window.size()) - 1);
    std::nth_element(window.begin(), at, window.end());
    kth[s] = std::sqrt(*at);
  });
  const auto median = kth.begin() + kCellSamples / 2;
  std::nth_element(kth.begin(), median, kth.end());
  return *median;
}

/// Scratch of one thread's block searches: the candidates of the (2s+1)³ cells around one cell.
class BlockSearch {
 public:
  BlockSearch(const Grid& grid, const std::vector<Vec3f>& points, double slack, Neighbourhoods& result)
      : grid_(grid), points_(points), slack_(slack), result_(result), best_(result.k), order_(result.k) {}

  /// Gathers the block of `shell` cells around cell g: (2s+1)² runs of 2s+1 cells along z, each contiguous in key
  /// order. False if it holds too many points (see kMaxCandidatesPerK).
  bool gather(const std::array<std::int64_t, 3>& g, std::int64_t shell) {
    g_ = g;
    shell_ = shell;
    const std::size_t side = static_cast<std::size_t>(2 * shell + 1);
    const std::size_t most = kMaxCandidatesPerK * result_.k * side * side / 9;
    cx_.clear(), cy_.clear(), cz_.clear(), cid_.clear();
    for (std::int64_t x = std::max<std::int64_t>(g[0] - shell, 0); x <= std::min(g[0] + shell, kAxisCells - 1); ++x)
      for (std::int64_t y = std::max<std::int64_t>(g[1] - shell, 0); y <= std::min(g[1] + shell, kAxisCells - 1);
           ++y) {
        const std::uint32_t from = grid_.first_at(Grid::key(x, y, std::max<std::int64_t>(g[2] - shell, 0)));
        const std::uint32_t to = grid_.first_at(Grid::key(x, y, g[2] + shell + 1));
        cx_.insert(cx_.end(), grid_.xs.begin() + from, grid_.xs.begin() + to);
        cy_.insert(cy_.end(), grid_.ys.begin() + from, grid_.ys.begin() + to);
        cz_.insert(cz_.end(), grid_.zs.begin() + from, grid_.zs.begin() + to);
        cid_.insert(cid_.end(), grid_.ids.begin() + from, grid_.ids.begin() + to);
        if (cid_.size() > most) return false;
      }
    dist_.resize(cid_.size()), near_dist_.resize(cid_.size()), near_id_.resize(cid_.size());
    previous_kth_ = std::numeric_limits<float>::infinity();
    return true;
  }

  /// The k-NN of the point at grid position j (in the gathered block's centre cell), written to the result; false
  /// if the block cannot certify them.
  bool search(std::size_t j) {
    const std::size_t k = result_.k, candidates = cid_.size();
    const std::uint32_t i = grid_.ids[j];
    const float qx = grid_.xs[j], qy = grid_.ys[j], qz = grid_.zs[j];
    const float* __restrict px = cx_.data();
    const float* __restrict py = cy_.data();
    const float* __restrict pz = cz_.data();
    const std::uint32_t* __restrict pid = cid_.data();
    float* __restrict pd = dist_.data();
    float* __restrict nd = near_dist_.data();
    std::uint32_t* __restrict ni = near_id_.data();
    for (std::size_t m = 0; m < candidates; ++m) pd[m] = squared_distance(qx, qy, qz, px[m], py[m], pz[m]);
    // Every point outside the block lies at least `reach` from point i: only candidates closer than that can make a
    // list the block certifies.
    double reach = std::numeric_limits<double>::infinity();
    const double cell = grid_.cell, shell = static_cast<double>(shell_);
    for (int a = 0; a < 3; ++a) {
      const double offset = static_cast<double>(points_[i][a]) - grid_.lo[a] - static_cast<double>(g_[a]) * cell;
      reach = std::min({reach, offset + shell * cell, (shell + 1) * cell - offset});
    }
    reach -= slack_;
    const float limit = reach > 0 ? static_cast<float>(reach * reach * (1 - 1e-5)) : 0.f;
    // First a tighter bound from the previous point: when k candidates pass it, they include the k nearest.
    float bound = std::min(limit, kPreviousBoundFactor * previous_kth_);
    std::size_t count = 0;
    for (;;) {
      count = 0;
      for (std::size_t m = 0; m < candidates; ++m) {
        nd[count] = pd[m];
        ni[count] = pid[m];
        count += (pd[m] < bound) & (pid[m] != i);
      }
      if (count >= k || bound == limit) break;
      bound = limit;
    }
    if (count < k) return false;
    // Rank of each close candidate by distance, branch-free; equal distances (ranked by index) and long lists take
    // the sort.
    bool sort = count > kRankMaxPerK * k;
    for (std::size_t a = 0; a < count && !sort; ++a) {
      std::uint32_t below = 0, equal = 0;
      for (std::size_t b = 0; b < count; ++b) {
        below += nd[b] < nd[a];
        equal += nd[b] == nd[a];
      }
      sort = equal > 1;
      if (below < k) order_[below] = static_cast<std::uint32_t>(a);
    }
    if (sort) {
      std::vector<std::uint64_t> all(count);
      for (std::size_t m = 0; m < count; ++m) all[m] = rank_key(nd[m], ni[m]);
      std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(k), all.end());
      std::copy(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(k), best_.begin());
    } else {
      for (std::size_t m = 0; m < k; ++m) best_[m] = rank_key(nd[order_[m]], ni[order_[m]]);
    }
    for (std::size_t m = 0; m < k; ++m) {
      result_.indices[i * k + m] = static_cast<std::uint32_t>(best_[m]);
      result_.distances[i * k + m] = std::sqrt(std::bit_cast<float>(static_cast<std::uint32_t>(best_[m] >> 32)));
    }
    previous_kth_ = std::bit_cast<float>(static_cast<std::uint32_t>(best_[k - 1] >> 32));
    return true;
  }

 private:
  const Grid& grid_;
  const std::vector<Vec3f>& points_;
  double slack_;
  Neighbourhoods& result_;
  std::array<std::int64_t, 3> g_{};
  std::int64_t shell_ = 1;
  float previous_kth_ = 0;
  std::vector<float> cx_, cy_, cz_, dist_, near_dist_;
  std::vector<std::uint64_t> best_;
  std::vector<std::uint32_t> order_, cid_, near_id_;
};

/// The k-NN of every point from a uniform grid of cells about as wide as a typical k-th neighbour distance. A point's
/// neighbours are sought among the 3×3×3 cells around its own, then among the 5×5×5 and 7×7×7, and kept when the
/// k-th lies closer than any point outside the block can; the few points left, and those of an overfull block, are
/// asked of the kd-tree. Both rank by the same float distances and break ties by index, so the lists are exactly those
/// the kd-tree alone gives.
/// False, with nothing written, for positions that are not finite or all coincide.
bool grid_neighbourhoods(const KdTree& tree, const std::vector<Vec3f>& points, Neighbourhoods& result,
                         const ProgressFn& progress) {
  if (!std::all_of(points.begin(), points.end(), [](const Vec3f& p) { return p.allFinite(); })) return false;
  const Box3f box = bounding_box(points);
  const double extent = (box.max - box.min).cast<double>().maxCoeff();
  // Cells at least extent/2^21 wide keep the keys in range.
  const double cell = std::max(kCellFactor * typical_kth_distance(points, result.k),
                               extent / static_cast<double>(kAxisCells - 2));
  if (!(cell > 0)) return false;
  const Grid grid = make_grid(points, box, cell);
  // Rounding of the cell coordinates (double) and of the float distances, with a wide margin.
  const double slack = 1e-9 * (grid.lo.cwiseAbs().maxCoeff() + extent);

  detail::parallel_chunks(grid.keys.size(), progress, "neighbourhoods", [&](std::size_t begin, std::size_t end) {
    BlockSearch block(grid, points, slack, result);
    std::vector<std::uint32_t> pending, left;
    for (std::size_t c = begin; c < end; ++c) {
      const std::uint64_t key = grid.keys[c];
      const std::array<std::int64_t, 3> g{static_cast<std::int64_t>(key >> 42),
                                          static_cast<std::int64_t>(key >> 21 & (kAxisCells - 1)),
                                          static_cast<std::int64_t>(key & (kAxisCells - 1))};
      pending.clear();
      for (std::uint32_t j = grid.starts[c]; j < grid.starts[c + 1]; ++j) pending.push_back(j);
      for (std::int64_t shell = 1; shell <= kMaxShell && !pending.empty() && block.gather(g, shell); ++shell) {
        left.clear();
        for (const std::uint32_t j : pending)
          if (!block.search(j)) left.push_back(j);
        pending.swap(left);
      }
      for (const std::uint32_t j : pending) tree_neighbours(tree, grid.ids[j], result);
    }
  });
  return true;
}

}  // namespace

Neighbourhoods compute_neighbourhoods(const KdTree& tree, const std::vector<Vec3f>& points,
                                      const NeighbourhoodOptions& options) {
  if (tree.size() != points.size())
    throw Error("neighbourhoods: the kd-tree holds " + std::to_string(tree.size()) + " points but the cloud has " +
                std::to_string(points.size()));
  Neighbourhoods result;
  const std::size_t n = points.size();
  result.k = n == 0 ? 0 : std::min(options.k, n - 1);
  const std::size_t k = result.k;
  result.indices.resize(n * k);
  result.distances.resize(n * k);
  if (k == 0) return result;
  if (k > kGridMaxK || n < kGridMinPoints || !grid_neighbourhoods(tree, points, result, options.progress)) {
    detail::parallel_chunks(n, options.progress, "neighbourhoods", [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) tree_neighbours(tree, i, result);
    });
  }
  return result;
}

}  // namespace pcsketch::neighbourhood
