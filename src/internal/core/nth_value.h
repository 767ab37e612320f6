#pragma once
// The value of a given rank among many floats, found in parallel (a serial nth_element over a million per-point
// values took about 10 ms on one core, several times a run).

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "pcsketch/core/assert.h"

namespace pcsketch::detail {

/// An unsigned key in the order of the floats (negative ones below +0, reversed).
inline std::uint32_t float_key(float v) {
  const auto bits = std::bit_cast<std::uint32_t>(v);
  return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

inline float key_float(std::uint32_t key) {
  return std::bit_cast<float>((key & 0x80000000u) ? (key & 0x7fffffffu) : ~key);
}

constexpr std::size_t kKeyBins = 1u << 16;

/// How many keys of `values` have each 16-bit lower digit among those whose upper digit is `high`, or, with
/// `upper`, each upper digit. Integer counts: the same sums in any order.
inline std::vector<std::size_t> digit_counts(std::span<const float> values, bool upper, std::uint32_t high) {
  tbb::enumerable_thread_specific<std::vector<std::size_t>> local([] { return std::vector<std::size_t>(kKeyBins); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, values.size(), 16384),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::vector<std::size_t>& count = local.local();
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        const std::uint32_t key = float_key(values[i]);
                        if (upper) ++count[key >> 16];
                        else if ((key >> 16) == high) ++count[key & 0xffffu];
                      }
                    });
  std::vector<std::size_t> total(kKeyBins, 0);
  for (const std::vector<std::size_t>& count : local)
    for (std::size_t b = 0; b < kKeyBins; ++b) total[b] += count[b];
  return total;
}

/// The digit whose bin holds the key of rank `rank` among the counted ones; `rank` becomes its rank inside the bin.
inline std::uint32_t digit_of_rank(const std::vector<std::size_t>& counts, std::size_t& rank) {
  std::uint32_t digit = 0;
  while (rank >= counts[digit]) rank -= counts[digit++];
  return digit;
}

/// The value that std::nth_element would put at `rank` of `values`, by two parallel 16-bit histogram passes over
/// their keys: exact, and the same for any thread count. Values must not be NaN; -0 counts below +0.
inline float nth_value(std::span<const float> values, std::size_t rank) {
  PCS_ASSERT(rank < values.size(), "nth_value: rank beyond the values");
  const std::uint32_t high = digit_of_rank(digit_counts(values, true, 0), rank);
  const std::uint32_t low = digit_of_rank(digit_counts(values, false, high), rank);
  return key_float((high << 16) | low);
}

}  // namespace pcsketch::detail
