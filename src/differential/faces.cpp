#include "faces.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "common.h"
#include "core/ordered_key.h"

namespace pcsketch::differential::detail {

namespace {

constexpr double kGapOverSpread = 3;     // a second face's gap over the spread of the point's own side
constexpr double kGapOverFarSpread = 2;  // and over the spread of the points beyond it

/// The new list of a split point: the nearest k of its own-face neighbours and their neighbours that lie within its
/// face's band of offsets, as keys (squared distance, index), nearest first (fewer only where they hold too few).
/// `seen`: two_step_ring's flags.
void own_face_list(const std::vector<Vec3f>& points, std::size_t i, const Vec3d& normal,
                   const neighbourhood::Neighbourhoods& nbh, const std::array<bool, neighbourhood::kMaxNeighbours>& own,
                   const FaceSplit& split, std::vector<std::uint8_t>& seen, std::vector<std::uint64_t>& keys) {
  two_step_ring(points, nbh, i, seen, keys, [&](std::size_t m) { return own[m]; });
  const Vec3d origin = points[i].cast<double>();
  std::erase_if(keys, [&](std::uint64_t key) {
    const double offset = normal.dot(points[pcsketch::detail::key_index(key)].cast<double>() - origin);
    return !(offset > split.low && offset < split.high);
  });
  const std::size_t k = std::min(nbh.k, keys.size());
  std::nth_element(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(k) - (k > 0), keys.end());
  keys.resize(k);
  std::sort(keys.begin(), keys.end());
}

}  // namespace

FaceSplit own_face(const std::vector<Vec3f>& points, std::size_t i, const std::uint32_t* nb, std::size_t k,
                   const Vec3d& normal, double gap, std::array<bool, neighbourhood::kMaxNeighbours>& own) {
  const Vec3d origin = points[i].cast<double>();
  std::array<std::pair<double, std::size_t>, neighbourhood::kMaxNeighbours + 1> offsets;
  for (std::size_t m = 0; m < k; ++m) offsets[m] = {normal.dot(points[nb[m]].cast<double>() - origin), m};
  offsets[k] = {0.0, k};  // the point itself
  std::sort(offsets.begin(), offsets.begin() + static_cast<std::ptrdiff_t>(k + 1));
  std::size_t self = 0;
  while (offsets[self].second != k) ++self;
  std::size_t low = self, high = self;
  while (low > 0 && offsets[low].first - offsets[low - 1].first <= gap) --low;
  while (high < k && offsets[high + 1].first - offsets[high].first <= gap) ++high;
  // A face parallel to the point's own stands off by far more than either side spreads; a crease's other face, rising
  // with the distance from the edge, spreads over as much as its gap.
  const double spread = offsets[high].first - offsets[low].first;
  const auto splits = [&](double gap_width, double far_spread) {
    return gap_width >= kGapOverSpread * spread && gap_width >= kGapOverFarSpread * far_spread;
  };
  const bool below = low > 0, above = high < k;
  if ((below && !splits(offsets[low].first - offsets[low - 1].first, offsets[low - 1].first - offsets[0].first)) ||
      (above && !splits(offsets[high + 1].first - offsets[high].first, offsets[k].first - offsets[high + 1].first)))
    return {.kept = k};
  own.fill(false);
  for (std::size_t r = low; r <= high; ++r)
    if (offsets[r].second != k) own[offsets[r].second] = true;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  return {.kept = high - low,
          .low = below ? 0.5 * (offsets[low - 1].first + offsets[low].first) : -kNone,
          .high = above ? 0.5 * (offsets[high].first + offsets[high + 1].first) : kNone};
}

std::size_t separate_faces(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                           const std::vector<std::uint32_t>& split, neighbourhood::Neighbourhoods& neighbourhoods) {
  const std::size_t k = neighbourhoods.k;
  // New lists first, written back after: the search reads the neighbours' lists as they were.
  std::vector<std::uint64_t> lists(split.size() * k, std::numeric_limits<std::uint64_t>::max());
  tbb::enumerable_thread_specific<std::vector<std::uint8_t>> flags(std::vector<std::uint8_t>(points.size(), 0));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, split.size(), 64), [&](const auto& r) {
    std::array<bool, neighbourhood::kMaxNeighbours> own;
    std::vector<std::uint64_t> keys;
    std::vector<std::uint8_t>& seen = flags.local();
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const std::size_t i = split[s];
      const Vec3d normal = normals[i].cast<double>();
      const std::uint32_t* nb = neighbourhoods.indices.data() + i * k;
      const float radius = neighbourhoods.distances[i * k + k - 1];
      const FaceSplit face = own_face(points, i, nb, k, normal, kFaceGap * radius, own);
      if (face.kept == k) continue;
      own_face_list(points, i, normal, neighbourhoods, own, face, seen, keys);
      if (keys.size() == k) std::copy(keys.begin(), keys.end(), lists.begin() + static_cast<std::ptrdiff_t>(s * k));
    }
  });
  const std::size_t changed = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, split.size(), 1024), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t count) {
        for (std::size_t s = r.begin(); s != r.end(); ++s) {
          if (lists[s * k] == std::numeric_limits<std::uint64_t>::max()) continue;
          ++count;
          for (std::size_t m = 0; m < k; ++m) {
            neighbourhoods.indices[split[s] * k + m] = pcsketch::detail::key_index(lists[s * k + m]);
            neighbourhoods.distances[split[s] * k + m] = std::sqrt(pcsketch::detail::key_value(lists[s * k + m]));
          }
        }
        return count;
      },
      std::plus<>());
  return changed;
}

}  // namespace pcsketch::differential::detail
