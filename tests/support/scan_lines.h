#pragma once
// A unit sphere as a line scanner records it: points on rings of constant latitude, denser along them than across.

#include <cmath>
#include <random>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::test {

/// `rings` circles of latitude evenly spread between the poles (both excluded), each sampled `density` times more
/// densely along it than the rings lie apart (a latitude step of the unit sphere); with Gaussian noise of σ = `noise`
/// latitude steps on each coordinate (seeded: the same cloud every time).
inline std::vector<Vec3f> sphere_rings(int rings, float density, float noise = 0.f, unsigned seed = 1) {
  const double pi = 3.14159265358979, step = pi / (rings + 1), along = step / density;
  std::mt19937 rng(seed);
  std::normal_distribution<double> jitter(0.0, noise * step);
  const auto offset = [&] { return noise > 0 ? jitter(rng) : 0.0; };
  std::vector<Vec3f> points;
  for (int r = 1; r <= rings; ++r) {
    const double latitude = -pi / 2 + r * step, radius = std::cos(latitude);
    const int count = static_cast<int>(std::ceil(2 * pi * radius / along));
    for (int i = 0; i < count; ++i) {
      // Each ring from its own phase, as a rotating scanner starts each line anywhere.
      const double longitude = 2 * pi * (i + 0.37 * r) / count;
      const double x = radius * std::cos(longitude) + offset(), y = std::sin(latitude) + offset(),
                   z = radius * std::sin(longitude) + offset();
      points.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
    }
  }
  return points;
}

}  // namespace pcsketch::test
