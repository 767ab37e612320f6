// gap_exceeds (a sieve over pseudo-angle bins, then sorted keys) against the largest gap measured with arctangents,
// and the sector pre-test that must never rule out a gap gap_exceeds finds.

#include "core/angular_gap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <random>

namespace pcsketch::detail {
namespace {

constexpr float kDeg = kGapPi / 180.f;

/// Directions to k random points of a disc squashed by `squash` along a random axis (a foreshortened neighbourhood),
/// with a random sector of `hole` radians emptied (a border).
std::vector<Vec2f> directions(std::mt19937& rng, int k, float squash, float hole) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const float axis = 2 * kGapPi * u(rng), start = 2 * kGapPi * u(rng);
  std::vector<Vec2f> dirs;
  while (static_cast<int>(dirs.size()) < k) {
    const float r = std::sqrt(u(rng)), t = 2 * kGapPi * u(rng);
    Vec2f p(r * std::cos(t), squash * r * std::sin(t));
    p = Vec2f(std::cos(axis) * p.x() - std::sin(axis) * p.y(), std::sin(axis) * p.x() + std::cos(axis) * p.y());
    const float from_start = std::remainder(std::atan2(p.y(), p.x()) - start, 2 * kGapPi);
    if (p.squaredNorm() > 1e-8f && !(from_start >= 0 && from_start < hole)) dirs.push_back(p);
  }
  return dirs;
}

TEST(AngularGap, GapExceedsAgreesWithTheMeasuredGap) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<float> angles;
  int compared = 0, over = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int k = 2 + static_cast<int>(u(rng) * 30);
    const float squash = u(rng) < 0.5f ? 1.f : 0.02f + u(rng);
    std::vector<Vec2f> dirs = directions(rng, k, squash, u(rng) < 0.5f ? 0.f : 4.f * u(rng));
    const float gap = largest_gap(angles, dirs).first;
    for (const float threshold_deg : {40.f, 60.f, 90.f, 120.f, 150.f, 200.f, 300.f}) {
      const float threshold = threshold_deg * kDeg;
      if (std::abs(gap - threshold) < 1e-3f) continue;  // within rounding of the threshold: either answer
      ASSERT_EQ(gap_exceeds(dirs, threshold), gap > threshold)
          << "trial " << trial << ", " << dirs.size() << " directions, gap " << gap / kDeg << " deg, threshold "
          << threshold_deg;
      ++compared;
      over += gap > threshold;
    }
  }
  // Both answers were asked many times.
  EXPECT_GT(over, compared / 10);
  EXPECT_LT(over, compared * 9 / 10);
}

TEST(AngularGap, ApproximateAngleWithinItsBound) {
  float worst = 0;
  for (int i = 0; i < 100000; ++i) {
    const double t = 2 * std::numbers::pi * i / 100000.0;
    for (const double r : {1e-20, 1.0, 1e20}) {
      const Vec2f d(static_cast<float>(r * std::cos(t)), static_cast<float>(r * std::sin(t)));
      const double exact = std::atan2(double(d.y()), double(d.x()));
      const double wrapped = std::remainder(double(approx_angle(d)) - exact, 2 * std::numbers::pi);
      worst = std::max(worst, static_cast<float>(std::abs(wrapped)));
      ASSERT_GE(approx_angle(d), 0.f);
      ASSERT_LE(approx_angle(d), 2 * kGapPi);
    }
  }
  EXPECT_LT(worst, kApproxAngleError);
}

TEST(AngularGap, SectorBitFollowsTheAngle) {
  constexpr double kStep = 2 * std::numbers::pi / 16;
  std::uint32_t seen = 0;
  const auto check = [&](double t, double r) {
    const Vec2f d(static_cast<float>(r * std::cos(t)), static_cast<float>(r * std::sin(t)));
    const std::uint16_t bit = sector_bit(d);
    ASSERT_EQ(std::popcount(bit), 1) << "angle " << t;
    const int s = std::countr_zero(bit);
    seen |= 1u << s;
    // The direction's own angle (after rounding to floats) lies in sector s, up to the rounding of its edges.
    const double angle = std::atan2(double(d.y()), double(d.x()));
    const double into = std::remainder(angle - s * kStep - kStep / 2, 2 * std::numbers::pi);
    ASSERT_LE(std::abs(into), kStep / 2 + 1e-6) << "angle " << angle << " in sector " << s;
  };
  for (int i = 0; i < 100000; ++i)
    for (const double r : {1e-20, 1.0, 1e20}) check(2 * std::numbers::pi * i / 100000.0, r);
  // The edges themselves and just either side of them.
  for (int e = 0; e < 16; ++e)
    for (const double offset : {-1e-3, -1e-6, -1e-8, 0.0, 1e-8, 1e-6, 1e-3}) check(e * kStep + offset, 1.0);
  EXPECT_EQ(seen, 0xFFFFu);
  // One direction well inside a sector of each quadrant.
  EXPECT_EQ(sector_bit(Vec2f(1.f, 0.2f)), 1u << 0);
  EXPECT_EQ(sector_bit(Vec2f(-0.2f, 1.f)), 1u << 4);
  EXPECT_EQ(sector_bit(Vec2f(-1.f, -0.2f)), 1u << 8);
  EXPECT_EQ(sector_bit(Vec2f(0.2f, -1.f)), 1u << 12);
}

std::uint16_t sectors_of(std::span<const Vec2f> dirs) {
  std::uint16_t filled = 0;
  for (const Vec2f& d : dirs) filled |= sector_bit(d);
  return filled;
}

Vec2f at(double angle) { return {static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle))}; }

/// A gap of `width` radians from `start` and directions spread over the rest of the circle, no two further apart than
/// `step`; sometimes also on the sector edges there.
std::vector<Vec2f> gap_of(std::mt19937& rng, double start, double width, double step) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2f> dirs{at(start), at(start + width)};
  const double end = start + 2 * std::numbers::pi;
  for (double a = start + width + step * u(rng); a < end - 1e-9; a += step * u(rng)) {
    const double edge = std::round(a / kSector) * kSector;
    dirs.push_back(at(u(rng) < 0.2 && edge > start + width && edge < end ? edge : a));
  }
  std::shuffle(dirs.begin(), dirs.end(), rng);
  return dirs;
}

TEST(AngularGap, SectorsNeverRuleOutAGapOverTheThreshold) {
  std::mt19937 rng(12111);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int answers[2] = {};  // gap_exceeds' noes and yeses
  for (const double degrees : {46.0, 60.0, 67.5, 90.0, 100.0, 112.5, 120.0, 135.0, 150.0, 180.0, 200.0, 337.5}) {
    const float threshold = static_cast<float>(degrees) * kDeg;
    for (int trial = 0; trial < 4000; ++trial) {
      // The gap starts anywhere or on a sector edge (to within float rounding), and ends just over or under the
      // threshold or anywhere about it.
      const double edge = kSector * std::floor(16 * u(rng));
      const double start = trial % 3 == 0 ? 2 * std::numbers::pi * u(rng) : edge + (u(rng) - 0.5) * 2e-6;
      const double offsets[] = {-1e-2, -1e-4, -2e-6, 2e-6, 1e-4, 1e-2, (u(rng) - 0.5)};
      const double width = threshold + offsets[trial % 7];
      if (width <= 0 || width >= 2 * std::numbers::pi - 1e-3) continue;
      const std::vector<Vec2f> dirs = gap_of(rng, start, width, std::min(width, 0.5) * 0.99);
      const bool exceeds = gap_exceeds(dirs, threshold);
      ASSERT_FALSE(exceeds && sectors_rule_out_gap(sectors_of(dirs), threshold))
          << degrees << " deg, gap from " << start << " of " << width << " rad";
      ++answers[exceeds];
    }
  }
  // Both answers were asked many times.
  EXPECT_GT(answers[0], 10000);
  EXPECT_GT(answers[1], 10000);
}

TEST(AngularGap, SectorsRuleOutMostNeighbourhoods) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<float> angles;
  int settled_inside = 0;
  // Even trials: round and whole neighbourhoods (inside a surface); odd: foreshortened or cut by a border.
  for (int trial = 0; trial < 20000; ++trial) {
    const bool inside = trial % 2 == 0;
    const std::vector<Vec2f> dirs = directions(rng, 16, inside ? 1.f : 0.2f + u(rng), inside ? 0.f : 4.f * u(rng));
    const bool out = sectors_rule_out_gap(sectors_of(dirs), 120 * kDeg);
    ASSERT_FALSE(out && gap_exceeds(dirs, 120 * kDeg)) << "trial " << trial;
    // Four empty sectors in a row are a gap of 90° at least: every gap under it is settled.
    const float gap = largest_gap(angles, dirs).first;
    ASSERT_TRUE(out || gap > 90 * kDeg - 1e-4f) << "trial " << trial << ", gap " << gap / kDeg << " deg";
    settled_inside += inside && out;
  }
  // Most neighbourhoods inside a surface are settled by the sectors, not sorted (the eight octants settled a third).
  EXPECT_GT(settled_inside, 10000 * 8 / 10);
}

TEST(AngularGap, SectorRunsAreAsLongAsTheThresholdNeeds) {
  // 120°: a gap over it holds 4 whole empty sectors (5.33 sectors wide, less the two it cuts).
  const float threshold = 120 * kDeg;
  EXPECT_TRUE(sectors_rule_out_gap(0xFFFFu, threshold));
  EXPECT_TRUE(sectors_rule_out_gap(static_cast<std::uint16_t>(~0b0111'0000u), threshold));   // 3 empty: no gap
  EXPECT_FALSE(sectors_rule_out_gap(static_cast<std::uint16_t>(~0b1111'0000u), threshold));  // 4 empty: maybe
  // Runs across bit 15 to bit 0 count too.
  EXPECT_FALSE(sectors_rule_out_gap(static_cast<std::uint16_t>(~0b1100'0000'0000'0011u), threshold));
  EXPECT_TRUE(sectors_rule_out_gap(static_cast<std::uint16_t>(~0b1000'0000'0000'0011u), threshold));
  // Thresholds of two sectors or less: a gap may hide in the edges of any two sectors.
  EXPECT_FALSE(sectors_rule_out_gap(0xFFFFu, 45 * kDeg));
  EXPECT_FALSE(sectors_rule_out_gap(0u, 350 * kDeg));
}

TEST(AngularGap, FewDirections) {
  const std::vector<Vec2f> one{{1.f, 0.f}};
  EXPECT_TRUE(gap_exceeds(one, 3.f));
  EXPECT_FALSE(gap_exceeds(one, 2 * kGapPi));
  const std::vector<Vec2f> opposite{{1.f, 0.f}, {-1.f, 1e-3f}};
  EXPECT_TRUE(gap_exceeds(opposite, 170 * kDeg));
  EXPECT_FALSE(gap_exceeds(opposite, 181 * kDeg));
}

}  // namespace
}  // namespace pcsketch::detail
