#include "pcsketch/neighbourhood/spatial_order.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <limits>

#include "pcsketch/core/error.h"

namespace pcsketch::neighbourhood {

namespace {

/// Spreads the low 21 bits of v so that two zero bits separate consecutive bits.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

struct Keyed {
  std::uint64_t code;
  std::uint32_t index;
  bool operator<(const Keyed& o) const { return code < o.code || (code == o.code && index < o.index); }
};

}  // namespace

std::vector<std::uint32_t> spatial_order(const std::vector<Vec3f>& points) {
  const std::size_t n = points.size();
  if (n >= std::numeric_limits<std::uint32_t>::max())
    throw Error("spatial order: " + std::to_string(n) + " points exceed the 32-bit index limit");
  const Box3f box = bounding_box(points);
  // One cubic grid of 2^21 cells per axis over the largest side keeps the curve isotropic.
  const float side = box.empty() ? 0.f : box.size().maxCoeff();
  const float scale = side > 0 ? static_cast<float>((1u << 21) - 1) / side : 0.f;
  std::vector<Keyed> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      std::uint64_t code = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const float t = (points[i][axis] - box.min[axis]) * scale;
        const float cell = t >= 0 ? std::min(t, float((1u << 21) - 1)) : 0.f;  // NaN maps to cell 0
        code |= spread_bits(static_cast<std::uint64_t>(cell)) << axis;
      }
      keyed[i] = {code, static_cast<std::uint32_t>(i)};
    }
  });
  // Keys are unique (index breaks ties), so the parallel sort is deterministic.
  tbb::parallel_sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = keyed[i].index;
  return order;
}

void reorder_spatially(PointCloud& cloud) { permute(cloud, spatial_order(cloud.positions)); }

}  // namespace pcsketch::neighbourhood
