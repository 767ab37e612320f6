#include "pcsketch/neighbourhood/spatial_order.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <limits>

#include "morton.h"
#include "pcsketch/core/error.h"

namespace pcsketch::neighbourhood {

using detail::MortonKeyed;

std::vector<std::uint32_t> spatial_order(const std::vector<Vec3f>& points) {
  const std::size_t n = points.size();
  if (n >= std::numeric_limits<std::uint32_t>::max())
    throw Error("spatial order: " + std::to_string(n) + " points exceed the 32-bit index limit");
  const Box3f box = bounding_box(points);
  // One cubic grid of 2^21 cells per axis over the largest side keeps the curve isotropic.
  const float side = box.empty() ? 0.f : box.size().maxCoeff();
  const float scale = side > 0 ? static_cast<float>(detail::kMortonMax) / side : 0.f;
  std::vector<MortonKeyed> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      std::array<std::uint32_t, 3> cell;
      for (int axis = 0; axis < 3; ++axis) {
        const float t = (points[i][axis] - box.min[axis]) * scale;
        cell[static_cast<std::size_t>(axis)] =
            static_cast<std::uint32_t>(t >= 0 ? std::min(t, float(detail::kMortonMax)) : 0.f);  // NaN: cell 0
      }
      keyed[i] = {detail::morton(cell[0], cell[1], cell[2]), static_cast<std::uint32_t>(i)};
    }
  });
  // Keys are unique (index breaks ties), so the parallel sort is deterministic.
  tbb::parallel_sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) order[i] = keyed[i].index;
  });
  return order;
}

void reorder_spatially(PointCloud& cloud) { permute(cloud, spatial_order(cloud.positions)); }

}  // namespace pcsketch::neighbourhood
