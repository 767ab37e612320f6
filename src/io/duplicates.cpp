// Exact duplicate points collapsed at load: k-NN of a point repeated m times finds only its copies, and the
// neighbourhood and spacing stages then take time quadratic in m (100,000 copies of one point: minutes).

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <utility>

#include "raw_cloud.h"

namespace pcsketch::io::detail {

namespace {

/// Buckets of points by the top bits of their hash: equal points share one, and a bucket's table stays in cache.
constexpr int kBucketBits = 8;

std::uint64_t hash_position(const Vec3d& p) {
  // +0.0 and -0.0 are the same point: adding 0.0 turns -0.0 into +0.0 before the bits are hashed.
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int d = 0; d < 3; ++d) {
    const auto bits = std::bit_cast<std::uint64_t>(p[d] + 0.0);
    h = (h ^ bits) * 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

/// The points grouped by bucket, in index order within each: their indices, positions and hashes side by side, so
/// that a bucket is read as one run.
struct Buckets {
  std::vector<std::uint32_t> start;  ///< per bucket and one more
  std::vector<std::uint32_t> index;
  std::vector<Vec3d> position;
  std::vector<std::uint64_t> hash;

  explicit Buckets(const std::vector<Vec3d>& positions) : start((std::size_t{1} << kBucketBits) + 1, 0) {
    const std::size_t n = positions.size();
    std::vector<std::uint64_t> h(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) h[i] = hash_position(positions[i]);
    });
    // A counting sort in parallel: each slice of the points counts its buckets, then writes its run of each bucket
    // after the runs of the slices before it, so a bucket holds its points in index order.
    const std::size_t slices = std::min<std::size_t>(64, (n + kSlicePoints - 1) / kSlicePoints);
    constexpr std::size_t kBuckets = std::size_t{1} << kBucketBits;
    std::vector<std::uint32_t> next(slices * kBuckets, 0);  // per slice and bucket: its count, then where it writes
    const auto slice_range = [&](std::size_t s) { return std::pair{s * n / slices, (s + 1) * n / slices}; };
    tbb::parallel_for(std::size_t{0}, slices, [&](std::size_t s) {
      const auto [first, last] = slice_range(s);
      for (std::size_t i = first; i < last; ++i) ++next[s * kBuckets + bucket_of(h[i])];
    });
    for (std::size_t b = 0, at = 0; b < kBuckets; ++b) {
      start[b] = static_cast<std::uint32_t>(at);
      for (std::size_t s = 0; s < slices; ++s)
        at += std::exchange(next[s * kBuckets + b], static_cast<std::uint32_t>(at));
    }
    start[kBuckets] = static_cast<std::uint32_t>(n);
    index.resize(n);
    position.resize(n);
    hash.resize(n);
    tbb::parallel_for(std::size_t{0}, slices, [&](std::size_t s) {
      const auto [first, last] = slice_range(s);
      for (std::size_t i = first; i < last; ++i) {
        const std::uint32_t at = next[s * kBuckets + bucket_of(h[i])]++;
        index[at] = static_cast<std::uint32_t>(i);
        position[at] = positions[i];
        hash[at] = h[i];
      }
    });
  }

 private:
  static constexpr std::size_t kSlicePoints = 16384;
  static std::size_t bucket_of(std::uint64_t hash) { return hash >> (64 - kBucketBits); }
};

/// Marks in `copy` every point of bucket b equal to an earlier one: open addressing over the bucket's first copies
/// (place + 1, 0 = empty), at most half full.
void mark_copies(const Buckets& buckets, std::size_t b, std::vector<std::uint8_t>& copy) {
  const std::uint32_t first = buckets.start[b], last = buckets.start[b + 1];
  const std::size_t size = std::bit_ceil(2 * std::size_t{last - first});
  std::vector<std::uint32_t> table(size, 0);
  for (std::uint32_t at = first; at < last; ++at) {
    const Vec3d& p = buckets.position[at];
    std::size_t slot = buckets.hash[at] & (size - 1);
    bool duplicate = false;
    for (; table[slot] != 0; slot = (slot + 1) & (size - 1))
      if (buckets.position[first + table[slot] - 1] == p) {
        duplicate = true;
        break;
      }
    if (duplicate)
      copy[buckets.index[at]] = 1;
    else
      table[slot] = at - first + 1;
  }
}

}  // namespace

std::size_t collapse_duplicates(RawCloud& raw) {
  const std::size_t n = raw.positions.size();
  // Indices are 32-bit, as everywhere downstream (the kd-tree refuses larger clouds).
  if (n < 2 || n >= 0xffffffffull) return 0;
  std::vector<std::uint8_t> copy(n, 0);
  {
    const Buckets buckets(raw.positions);
    tbb::parallel_for(std::size_t{0}, buckets.start.size() - 1, [&](std::size_t b) { mark_copies(buckets, b, copy); });
  }
  if (std::find(copy.begin(), copy.end(), std::uint8_t{1}) == copy.end()) return 0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (copy[i]) continue;
    // The first copy is kept, with its normal and colour.
    if (kept != i) {
      raw.positions[kept] = raw.positions[i];
      if (!raw.normals.empty()) raw.normals[kept] = raw.normals[i];
      if (!raw.colors.empty()) raw.colors[kept] = raw.colors[i];
      for (PointAttribute& a : raw.attributes) a.values[kept] = a.values[i];
    }
    ++kept;
  }
  raw.positions.resize(kept);
  if (!raw.normals.empty()) raw.normals.resize(kept);
  if (!raw.colors.empty()) raw.colors.resize(kept);
  for (PointAttribute& a : raw.attributes) a.values.resize(kept);
  return n - kept;
}

}  // namespace pcsketch::io::detail
