// nth_value (two parallel histogram passes over order-preserving keys) against std::nth_element.

#include "core/nth_value.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <limits>
#include <random>
#include <vector>

namespace pcsketch::detail {
namespace {

float by_nth_element(std::vector<float> values, std::size_t rank) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

TEST(NthValue, KeysKeepTheOrderOfFloats) {
  const std::vector<float> ordered{-std::numeric_limits<float>::infinity(), -3.5f, -1e-30f, 0.f, 1e-38f, 2.f,
                                   std::numeric_limits<float>::max(), std::numeric_limits<float>::infinity()};
  for (std::size_t i = 0; i + 1 < ordered.size(); ++i) EXPECT_LT(float_key(ordered[i]), float_key(ordered[i + 1]));
  for (const float v : ordered) EXPECT_EQ(std::bit_cast<std::uint32_t>(key_float(float_key(v))),
                                          std::bit_cast<std::uint32_t>(v));
}

TEST(NthValue, MatchesNthElementAtEveryRankTried) {
  std::mt19937 rng(7);
  std::normal_distribution<float> normal(0.f, 3.f);
  std::uniform_int_distribution<int> small(0, 20);
  for (const std::size_t n : {1u, 2u, 3u, 1000u, 200001u}) {
    std::vector<float> values(n);
    // Half repeated small integers (ties across the bins of the first pass), half spread values of both signs.
    for (std::size_t i = 0; i < n; ++i) values[i] = i % 2 ? static_cast<float>(small(rng)) : normal(rng);
    for (const std::size_t rank : {std::size_t{0}, n / 4, n / 2, n - 1})
      EXPECT_EQ(nth_value(values, rank), by_nth_element(values, rank)) << n << " values, rank " << rank;
  }
}

TEST(NthValue, RejectsARankBeyondTheValues) {
  const std::vector<float> values{1.f, 2.f};
  EXPECT_THROW(nth_value(values, 2), Error);
  EXPECT_THROW(nth_value({}, 0), Error);
}

}  // namespace
}  // namespace pcsketch::detail
