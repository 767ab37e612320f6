// Sorting Morton-keyed points: by the top bits of the code into buckets, then each bucket on its own.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <utility>

#include "morton.h"

namespace pcsketch::neighbourhood::detail {

namespace {

constexpr int kBucketBits = 12;  // 16 coarse cells per axis: about a thousand points a bucket at 1M on a surface
constexpr std::size_t kBuckets = std::size_t{1} << kBucketBits;
constexpr std::size_t kChunks = 16;  // counted and placed in parallel

std::size_t bucket_of(const MortonKeyed& k) {
  return static_cast<std::size_t>(k.code >> (3 * kMortonBits - kBucketBits));
}

}  // namespace

void sort_keyed(std::vector<MortonKeyed>& keyed) {
  const std::size_t n = keyed.size();
  if (n < 16 * kBuckets) {
    std::sort(keyed.begin(), keyed.end());
    return;
  }
  // Each chunk's points counted per bucket, then placed in their bucket after the earlier chunks' (in parallel);
  // keys are unique (the index breaks ties), so the sorted buckets are the one sorted order.
  const std::size_t chunk = (n + kChunks - 1) / kChunks;
  std::vector<std::array<std::uint32_t, kBuckets>> place(kChunks);
  tbb::parallel_for(std::size_t{0}, kChunks, [&](std::size_t c) {
    place[c].fill(0);
    for (std::size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) ++place[c][bucket_of(keyed[i])];
  });
  std::vector<std::uint32_t> start(kBuckets + 1, 0);
  std::uint32_t at = 0;
  for (std::size_t b = 0; b < kBuckets; ++b) {
    start[b] = at;
    for (std::size_t c = 0; c < kChunks; ++c) at += std::exchange(place[c][b], at);
  }
  start[kBuckets] = at;
  std::vector<MortonKeyed> out(n);
  tbb::parallel_for(std::size_t{0}, kChunks, [&](std::size_t c) {
    for (std::size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i)
      out[place[c][bucket_of(keyed[i])]++] = keyed[i];
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kBuckets, 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) std::sort(out.begin() + start[b], out.begin() + start[b + 1]);
  });
  keyed.swap(out);
}

}  // namespace pcsketch::neighbourhood::detail
