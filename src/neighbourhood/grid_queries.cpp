// The kd-tree's single-point queries answered from the neighbourhoods' grid where it proves them: a clean cloud then
// never builds the tree (its serial build was 4% of a 1M-point draw).

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "grid_cells.h"
#include "grid_knn.h"

namespace pcsketch::neighbourhood::detail {

namespace {

/// Misses after which the single-point queries go straight to the tree: a cloud the grid serves badly (scan lines
/// far apart, stray points) would pay for the cubes and then the tree.
constexpr std::uint32_t kMostMisses = 64;

}  // namespace

bool GridKnn::knn_of_point(std::size_t i, std::size_t k, std::vector<std::uint32_t>& indices,
                           std::vector<float>& distances) const {
  const Impl& g = *impl_;
  if (!g.grid || k == 0 || g.misses.load(std::memory_order_relaxed) >= kMostMisses) return false;
  // The cube whose inscribed disc is expected to hold k points on a surface, then one cell wider.
  const int reach = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(k) / (std::numbers::pi * g.per_cell)))));
  thread_local Candidates cand;
  if (!g.prove(cand, i, k, reach) && !g.prove(cand, i, k, reach + 1)) {
    g.misses.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  indices.resize(k);
  distances.resize(k);
  for (std::size_t m = 0; m < k; ++m) {
    indices[m] = key_index(cand.keys[m]);
    distances[m] = std::sqrt(key_value(cand.keys[m]));
  }
  return true;
}

bool GridKnn::within(const Vec3f& q, float radius, std::vector<std::uint32_t>& indices) const {
  const Impl& g = *impl_;
  indices.clear();
  if (!(radius >= 0)) return true;  // as the tree: no point
  if (!g.grid) return false;
  const Frame& frame = g.grid->frame;
  // A point within the radius lies at most this many cells from q's along each axis (cell coordinates are floors,
  // clamped: neither moves two points further apart); the margin covers the rounding of the divisions.
  const double span = double(radius) / frame.edge;
  constexpr int kMostReach = 6;
  if (!(span < kMostReach)) return false;
  const int reach = static_cast<int>(std::ceil(span * (1 + 1e-6) + 1e-9));
  if (reach > kMostReach) return false;
  const Cell centre = frame.cell_of(q);
  // Squared distance from q to the slab of the cells `d` away along each axis, in cells (0 for its own): a cell
  // whose box lies beyond the radius is skipped. q may lie outside its (clamped) cell: then 0 where it would be
  // negative, which only keeps more cells.
  std::array<std::array<double, 2 * kMostReach + 1>, 3> slab{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double t = (double(q[static_cast<Eigen::Index>(a)]) - frame.lo[static_cast<Eigen::Index>(a)]) / frame.edge -
                     double(centre[a]);
    for (int d = -reach; d <= reach; ++d) {
      const double gap = std::max(0.0, d > 0 ? d - t : d < 0 ? t - (d + 1) : 0.0);
      slab[a][static_cast<std::size_t>(d + reach)] = gap * gap;
    }
  }
  const double limit = span * span * (1 + 1e-5) + 1e-9;
  // Squared distances surely inside and surely outside the radius (none where its square is subnormal).
  const float r2 = radius * radius;
  const bool squares = r2 >= std::numeric_limits<float>::min();
  const float near = squares ? r2 * (1 - 1e-5f) : 0.f, far = squares ? r2 * (1 + 1e-5f) : INFINITY;
  for (int dz = -reach; dz <= reach; ++dz)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        if (slab[0][std::size_t(dx + reach)] + slab[1][std::size_t(dy + reach)] + slab[2][std::size_t(dz + reach)] >
            limit)
          continue;
        const std::int64_t cx = std::int64_t(centre[0]) + dx, cy = std::int64_t(centre[1]) + dy,
                           cz = std::int64_t(centre[2]) + dz;
        if (std::min({cx, cy, cz}) < 0 || std::max({cx, cy, cz}) > kMortonMax) continue;
        const std::int64_t cell = g.grid->find(morton(std::uint32_t(cx), std::uint32_t(cy), std::uint32_t(cz)));
        if (cell < 0) continue;
        for (std::uint32_t r = g.grid->start[std::size_t(cell)]; r < g.grid->start[std::size_t(cell) + 1]; ++r) {
          const std::uint32_t j = g.grid->order[r];
          const Vec3f& p = g.points[j];
          // As the tree's inclusive test: the root of nanoflann's squared distance against the radius, taken only
          // near it (the squares' rounding is 1e-7).
          const float d2 = squared(q.x() - p.x(), q.y() - p.y(), q.z() - p.z());
          if (d2 > far) continue;
          if (d2 < near || std::sqrt(d2) <= radius) indices.push_back(j);
        }
      }
  return true;
}

}  // namespace pcsketch::neighbourhood::detail
