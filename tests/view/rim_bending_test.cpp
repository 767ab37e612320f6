// The bending test of interior rim samples: n·v flat around a sample (noise on a face seen edge-on) against n·v that
// changes with position (a cylinder's rim), at the same normal noise.

#include "rim_bending.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::view::detail {
namespace {

constexpr float kNoise = 0.05f;  // radians of normal noise, about what a denoised σ = 0.1% cloud keeps
constexpr float kMinF = 16.f;    // ContourOptions::bend_min_f's default

struct Patch {
  std::vector<Vec3f> positions, normals;
  std::vector<float> facing;  // n·v for a view along +x
  std::vector<std::uint32_t> asked;
};

/// Unit normals tilted at random by about kNoise, n·v for the view direction +x, and the points within `band` of
/// x = 0 (where a plane seen edge-on and a cylinder's rim both flip the sign of n·v) as the asked samples.
void finish(Patch& patch, std::mt19937& rng, float band) {
  std::normal_distribution<float> tilt(0.f, kNoise);
  for (std::uint32_t i = 0; i < patch.positions.size(); ++i) {
    Vec3f& n = patch.normals[i];
    n = (n + Vec3f(tilt(rng), tilt(rng), tilt(rng))).normalized();
    patch.facing.push_back(n.x());
    if (std::abs(patch.positions[i].x()) < band) patch.asked.push_back(i);
  }
}

std::size_t bending(const Patch& patch) {
  std::optional<neighbourhood::KdTree> tree;
  const neighbourhood::Neighbourhoods nbh = neighbourhood::index_neighbourhoods(patch.positions, tree, {.k = 16});
  const std::vector<char> bends = rim_bends(patch.positions, patch.normals, nbh, patch.facing, patch.asked, 8, kMinF);
  std::size_t count = 0;
  for (const char b : bends) count += b != 0;
  return count;
}

// A plane seen edge-on (normal +z, view along +x: n·v is 0 but for the noise) against a thin cylinder around y seen
// along +x (a rim of fine relief: radius 0.05, about 15 spacings), 20k random points on each.
TEST(RimBending, NoiseOnAFaceSeenEdgeOnDoesNotBendButARimDoes) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  Patch plane, cylinder;
  for (int i = 0; i < 20000; ++i) {
    plane.positions.emplace_back(u(rng), u(rng), 0.f);
    plane.normals.emplace_back(0.f, 0.f, 1.f);
    // The top of the cylinder, within 1.2 rad of +z: the normal's x component crosses 0 at x = 0, where the view
    // along +x grazes it.
    const float a = 1.2f * u(rng);
    cylinder.positions.emplace_back(0.05f * std::sin(a), u(rng), 0.05f * std::cos(a));
    cylinder.normals.emplace_back(std::sin(a), 0.f, std::cos(a));
  }
  finish(plane, rng, 0.01f);
  finish(cylinder, rng, 0.005f);
  ASSERT_GT(plane.asked.size(), 150u);
  ASSERT_GT(cylinder.asked.size(), 150u);
  // Measured: none of the plane's 208, 87% of the cylinder's 1,679. A chain is kept when half its samples bend.
  EXPECT_LT(bending(plane), plane.asked.size() / 50);
  EXPECT_GT(bending(cylinder), cylinder.asked.size() * 3 / 4);
}

}  // namespace
}  // namespace pcsketch::view::detail
