// gap_exceeds (a sieve over pseudo-angle bins, then sorted keys) against the largest gap measured with arctangents.

#include "core/angular_gap.h"

#include <gtest/gtest.h>

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
