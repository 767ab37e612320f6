#include "image_cells.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/nth_value.h"

namespace pcsketch::view::detail {
namespace {

/// A cell coordinate as an unsigned 32-bit number that orders like it (clamped far beyond any image).
std::uint64_t cell_coordinate(float x, float cell) {
  const double c = std::floor(static_cast<double>(x) / cell);
  const double limit = std::numeric_limits<std::int32_t>::max();
  return static_cast<std::uint64_t>(std::clamp(std::isfinite(c) ? c : 0.0, -limit, limit) + limit);
}

}  // namespace

std::vector<std::uint32_t> first_in_image_cells(const std::vector<Vec3f>& projected, std::vector<std::uint32_t> valid,
                                                float cell) {
  if (!(cell > 0) || valid.size() < 2) return valid;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(valid.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, valid.size(), 4096), [&](const auto& r) {
    for (std::size_t v = r.begin(); v < r.end(); ++v) {
      const Vec3f& p = projected[valid[v]];
      keyed[v] = {cell_coordinate(p.x(), cell) << 32 | cell_coordinate(p.y(), cell), valid[v]};
    }
  });
  tbb::parallel_sort(keyed.begin(), keyed.end());  // (cell, index) pairs are unique: the same order on any run
  // Marks, then one pass in index order: the kept indices come out increasing without a second sort.
  std::vector<char> first(projected.size(), 0);
  for (std::size_t k = 0; k < keyed.size(); ++k)
    if (k == 0 || keyed[k].first != keyed[k - 1].first) first[keyed[k].second] = 1;
  std::erase_if(valid, [&](std::uint32_t i) { return !first[i]; });
  return valid;
}

float low_spacing(const std::vector<float>& spacing_px, const std::vector<std::uint32_t>& valid) {
  if (valid.empty()) return 0.f;
  std::vector<float> s(valid.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, valid.size(), 16384), [&](const auto& r) {
    for (std::size_t v = r.begin(); v < r.end(); ++v) s[v] = spacing_px[valid[v]];
  });
  return pcsketch::detail::nth_value(s, s.size() / 20);
}

}  // namespace pcsketch::view::detail
