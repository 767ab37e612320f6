#include "pcsketch/neighbourhood/spatial_order.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "morton.h"
#include "pcsketch/core/error.h"

namespace pcsketch::neighbourhood {

using detail::MortonKeyed;

std::vector<std::uint32_t> spatial_order(const std::vector<Vec3f>& points) {
  const std::size_t n = points.size();
  if (n >= std::numeric_limits<std::uint32_t>::max())
    throw Error("spatial order: " + std::to_string(n) + " points exceed the 32-bit index limit");
  const detail::FinestCells cells(bounding_box(points));
  std::vector<MortonKeyed> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i)
      keyed[i] = {cells.code_of(points[i]), static_cast<std::uint32_t>(i)};
  });
  detail::sort_keyed(keyed);
  std::vector<std::uint32_t> order(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) order[i] = keyed[i].index;
  });
  return order;
}

void reorder_spatially(PointCloud& cloud) { permute(cloud, spatial_order(cloud.positions)); }

}  // namespace pcsketch::neighbourhood
