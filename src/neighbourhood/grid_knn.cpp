// The k-NN of every point from the 27 grid cells around it: each cell's candidates are gathered once for all of its
// points, with no tree descent per query. Rows the grid cannot prove are left to the kd-tree.

#include "grid_knn.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "core/ordered_key.h"
#include "core/parallel_chunks.h"
#include "grid_cells.h"
#include "morton.h"

namespace pcsketch::neighbourhood::detail {
namespace {

/// Every point's finest code and index, sorted (a cloud in spatial order, the pipeline's, costs one pass).
std::vector<MortonKeyed> sorted_codes(const std::vector<Vec3f>& points, const FinestCells& cells) {
  std::vector<MortonKeyed> keyed(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) keyed[i] = {cells.code_of(points[i]), std::uint32_t(i)};
  });
  if (!std::is_sorted(keyed.begin(), keyed.end())) sort_keyed(keyed);
  return keyed;
}

/// The cell edge at which an occupied cell holds about `target` points on average. Occupancy is counted at every
/// power-of-two edge in one pass over the finest sorted codes (two neighbours in code order share a cell of level j
/// unless their codes differ above bit 3j), then interpolated between the two levels around the target with the
/// local growth rate (4 per level on a surface, 8 in a volume).
double cell_edge(const std::vector<Vec3f>& points, const Box3f& box, double target) {
  const double finest = double(box.size().maxCoeff()) / kMortonMax;
  const std::vector<MortonKeyed> keyed = sorted_codes(points, FinestCells(box));
  std::array<double, kMortonBits + 2> above{};  // above[j]: neighbours in different cells of level j
  for (std::size_t i = 1; i < keyed.size(); ++i) {
    const std::uint64_t x = keyed[i].code ^ keyed[i - 1].code;
    if (x == 0) continue;
    const int level = (63 - std::countl_zero(x)) / 3;
    for (int j = 0; j <= level; ++j) above[static_cast<std::size_t>(j)] += 1;
  }
  const auto occupancy = [&](int j) { return double(points.size()) / (1.0 + above[static_cast<std::size_t>(j)]); };
  int j = 0;
  while (j <= kMortonBits && occupancy(j) < target) ++j;
  if (j == 0) return finest;
  const double growth = std::clamp(std::log2(occupancy(j) / occupancy(j - 1)), 1.0, 3.0);
  return finest * std::ldexp(1.0, j) * std::pow(target / occupancy(j), 1.0 / growth);
}

/// A row's first bound is the k-th distance of the point before times this: wide enough for all but about 1 in 10
/// rows (1M bunny), with about 1.5 k candidates within it instead of 2.75 k under the triangle bound.
constexpr float kGuess = 1.15f;

/// Row i from the k nearest that `cand` found, nearest first.
void store(const Candidates& cand, std::size_t i, std::size_t k, std::uint32_t* indices, float* distances) {
  for (std::size_t m = 0; m < k; ++m) {
    indices[i * k + m] = key_index(cand.keys[m]);
    distances[i * k + m] = std::sqrt(key_value(cand.keys[m]));
  }
}

/// The rows the 27 cells left (`left`), from the 125 then the 343 cells around where they are few: a sparse patch's
/// rows, which would otherwise build the kd-tree for a handful of points (43 of a 1M bunny sample). Many left rows
/// (stray points, crowded copies) are the tree's: its build costs less than their cubes. Clears left[i] of the rows
/// it fills.
void fill_wide(const GridKnn::Impl& g, std::size_t k, std::vector<std::uint8_t>& left, std::uint32_t* indices,
               float* distances) {
  std::vector<std::uint32_t> rest;
  for (std::uint32_t i = 0; i < left.size(); ++i)
    if (left[i]) rest.push_back(i);
  if (rest.empty() || rest.size() > left.size() / 256) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rest.size(), 1), [&](const auto& r) {
    thread_local Candidates cand;
    for (std::size_t c = r.begin(); c < r.end(); ++c)
      if (g.prove(cand, rest[c], k, 2) || g.prove(cand, rest[c], k, 3)) {
        store(cand, rest[c], k, indices, distances);
        left[rest[c]] = 0;
      }
  });
}

/// The rows the 27 cells around each point's own prove (see GridKnn::fill); clears their places in `left`.
void fill_near(const GridKnn::Impl& g, std::size_t k, std::vector<std::uint8_t>& left, std::uint32_t* indices,
               float* distances, const ProgressFn& progress) {
  const Grid& grid = *g.grid;
  const std::vector<Vec3f>& points = g.points;
  pcsketch::detail::parallel_chunks(
      grid.cells(), progress, "neighbourhoods",
      [&](std::size_t begin, std::size_t end) {
        thread_local Candidates cand;
        // Bounds for a row from the point before (in this cell or the one before): its k-th distance a little
        // widened, a guess that holds for most points, then that distance plus the step between the two, within
        // which the point before and its k nearest lie (triangle inequality), then none.
        float reach = INFINITY;
        Vec3f previous = Vec3f::Zero();
        for (std::size_t cell = begin; cell < end; ++cell) {
          cand.gather(grid, points, cell);
          if (cand.index.size() > g.most) continue;
          for (std::uint32_t r = grid.start[cell]; r < grid.start[cell + 1]; ++r) {
            const std::uint32_t i = grid.order[r];
            const float guess = reach * kGuess;
            const float bound = (reach + (points[i] - previous).norm()) * (1 + 1e-5f);
            reach = INFINITY;
            cand.measure(points[i]);
            if (!cand.nearest(i, k, guess * guess) && !(bound > guess && cand.nearest(i, k, bound * bound)) &&
                !cand.nearest(i, k, INFINITY))
              continue;
            const float kth = std::sqrt(key_value(cand.keys[k - 1]));
            reach = kth;
            previous = points[i];
            // A margin far above float rounding: a point outside the 27 cells can neither be nearer nor tie.
            if (!(double(kth) < way_out(grid.frame, points[i], cand.centre) * (1 - 1e-5))) continue;
            store(cand, i, k, indices, distances);
            left[i] = 0;
          }
        }
      },
      16);
}

}  // namespace

GridKnn::GridKnn(const std::vector<Vec3f>& points, std::size_t k)
    : impl_(std::make_unique<Impl>(points, 64 * (k + 1), 0.5 * double(k + 1))) {
  const Box3f box = bounding_box(points);
  if (!box.empty() && box.size().allFinite() && box.size().maxCoeff() > 0)
    impl_->grid.emplace(points, Frame{box.min.cast<double>(), cell_edge(points, box, impl_->per_cell)});
}

GridKnn::~GridKnn() = default;

std::vector<std::uint32_t> GridKnn::fill(std::size_t k, std::uint32_t* indices, float* distances,
                                         const ProgressFn& progress) const {
  std::vector<std::uint8_t> left(impl_->points.size(), 1);
  if (impl_->grid) {
    fill_near(*impl_, k, left, indices, distances, progress);
    fill_wide(*impl_, k, left, indices, distances);
  }
  std::vector<std::uint32_t> rest;
  for (std::uint32_t i = 0; i < left.size(); ++i)
    if (left[i]) rest.push_back(i);
  return rest;
}

}  // namespace pcsketch::neighbourhood::detail
