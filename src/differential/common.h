#pragma once
// Helpers shared by the differential stages.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "core/ordered_key.h"
#include "pcsketch/core/error.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential::detail {

/// Neighbours a stage uses: `requested`, or all of the shared neighbourhood when 0 (never more than it holds).
inline std::size_t neighbours_used(std::size_t requested, const neighbourhood::Neighbourhoods& neighbourhoods) {
  return requested == 0 ? neighbourhoods.k : std::min(requested, neighbourhoods.k);
}

/// Every stride-th point makes a sample, so that about `max_samples` are taken (at most twice as many).
inline std::size_t sample_stride(std::size_t n, std::size_t max_samples) {
  return std::max<std::size_t>(1, n / std::max<std::size_t>(max_samples, 1));
}

/// Throws unless the neighbourhoods were computed for these `count` points.
inline void check_neighbourhoods(std::string_view stage, std::size_t count,
                                 const neighbourhood::Neighbourhoods& neighbourhoods) {
  const bool trivial = neighbourhoods.k == 0 && neighbourhoods.indices.empty() && count <= 1;
  if (neighbourhoods.size() != count && !trivial)
    throw Error(std::string(stage) + ": the neighbourhoods cover " + std::to_string(neighbourhoods.size()) +
                " points but the cloud has " + std::to_string(count));
}

/// Each point's distance to its k-th (farthest) shared neighbour, gathered in parallel; k must be positive.
inline std::vector<float> farthest_distances(const neighbourhood::Neighbourhoods& neighbourhoods) {
  const std::size_t k = neighbourhoods.k, n = neighbourhoods.size();
  std::vector<float> farthest(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) farthest[i] = neighbourhoods.distances[i * k + k - 1];
  });
  return farthest;
}

/// The points one or two steps from i along the lists (i left out), each once, as ordered keys of their squared
/// distances from i, into `keys`. `seen`, a flag a point, must come clear and is left clear: it dedupes without the
/// sort of the ring's few hundred entries, which was most of its cost. `through(m)` chooses the m-th neighbours of i
/// the ring passes through (the others and their lists are left out); by default all.
template <typename Through = bool (*)(std::size_t)>
void two_step_ring(
    const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& nbh, std::size_t i,
    std::vector<std::uint8_t>& seen, std::vector<std::uint64_t>& keys,
    Through through = [](std::size_t) { return true; }) {
  // Every key is written and counted only if new: whether a point was seen is a coin toss, and a branch on it
  // mispredicted half the time (a tenth of a draw whose denoising takes the wider lists).
  const std::span<const std::uint32_t> first = nbh.of(i);
  keys.resize(first.size() * (nbh.k + 1));
  std::size_t count = 0;
  seen[i] = 1;
  const auto add = [&](std::uint32_t j) {
    keys[count] = pcsketch::detail::ordered_key((points[j] - points[i]).squaredNorm(), j);
    count += seen[j] ^ 1u;
    seen[j] = 1;
  };
  for (std::size_t m = 0; m < first.size(); ++m) {
    if (!through(m)) continue;
    add(first[m]);
    for (const std::uint32_t q : nbh.of(first[m])) add(q);
  }
  keys.resize(count);
  seen[i] = 0;
  for (const std::uint64_t key : keys) seen[pcsketch::detail::key_index(key)] = 0;
}

}  // namespace pcsketch::differential::detail
