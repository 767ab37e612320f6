// The bucketed Morton sort must give std::sort's order exactly, whatever the spread of the codes.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "morton.h"

namespace pcsketch::neighbourhood::detail {
namespace {

/// Sorted copies by sort_keyed and by std::sort are equal.
void expect_as_std_sort(std::vector<MortonKeyed> keyed) {
  std::vector<MortonKeyed> expected = keyed;
  std::sort(expected.begin(), expected.end());
  sort_keyed(keyed);
  ASSERT_EQ(keyed.size(), expected.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    ASSERT_EQ(keyed[i].code, expected[i].code) << i;
    ASSERT_EQ(keyed[i].index, expected[i].index) << i;
  }
}

TEST(MortonSort, MatchesStdSortOnSpreadCrowdedAndTinyInputs) {
  std::mt19937_64 rng(5);
  const std::uint64_t full = (std::uint64_t{1} << (3 * kMortonBits)) - 1;
  std::uniform_int_distribution<std::uint64_t> any(0, full);
  // Spread over every bucket, with repeated codes (ties broken by index) and the extreme codes.
  std::vector<MortonKeyed> spread(300000);
  for (std::uint32_t i = 0; i < spread.size(); ++i) spread[i] = {i % 7 == 0 ? spread[i / 2].code : any(rng), i};
  spread[5].code = 0;
  spread[6].code = full;
  expect_as_std_sort(spread);
  // Everything in one bucket: codes below its top bits only.
  std::vector<MortonKeyed> crowded(200000);
  std::uniform_int_distribution<std::uint64_t> low(0, 1000);
  for (std::uint32_t i = 0; i < crowded.size(); ++i) crowded[i] = {low(rng), 199999 - i};
  expect_as_std_sort(crowded);
  // Below the bucketing size, and empty.
  std::vector<MortonKeyed> tiny(100);
  for (std::uint32_t i = 0; i < tiny.size(); ++i) tiny[i] = {any(rng), i};
  expect_as_std_sort(tiny);
  expect_as_std_sort({});
}

}  // namespace
}  // namespace pcsketch::neighbourhood::detail
