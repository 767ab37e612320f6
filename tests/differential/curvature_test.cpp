// Known-answer tests of normals, orientation and principal curvatures on analytic shapes.

#include "pcsketch/differential/curvature.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pcsketch/differential/surface.h"
#include "support/analytic_shapes.h"

namespace pcsketch::differential {
namespace {

/// Analyses `cloud` with its file normals dropped; the cloud is reordered in place, `truth` (the generator's exact
/// normals) follows through source_index.
struct Analysed {
  PointCloud cloud;
  std::vector<Vec3f> truth;
  Surface surface;
};

Analysed analyse(PointCloud cloud, const SurfaceOptions& options = {}) {
  Analysed a;
  const std::vector<Vec3f> truth = cloud.normals;
  cloud.normals.clear();
  a.surface = analyse_surface(cloud, options);
  a.truth.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) a.truth[i] = truth[cloud.source_index[i]];
  a.cloud = std::move(cloud);
  return a;
}

/// Fraction of the points passing `keep` for which `ok` holds.
template <class Keep, class Ok>
double fraction(std::size_t n, Keep keep, Ok ok) {
  std::size_t kept = 0, good = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep(i)) continue;
    ++kept;
    good += ok(i) ? 1 : 0;
  }
  return kept ? static_cast<double>(good) / static_cast<double>(kept) : 0.0;
}

constexpr auto kAll = [](std::size_t) { return true; };

TEST(Curvature, SphereWithinThreePercent) {
  const float r = 2.f;
  const Analysed a = analyse(test::sphere(r, {.n = 20000, .seed = 7}));
  const Curvature& c = a.surface.curvature;
  const double within = fraction(a.cloud.size(), kAll, [&](std::size_t i) {
    return std::abs(c.k1[i] * r - 1.f) < 0.03f && std::abs(c.k2[i] * r - 1.f) < 0.03f;
  });
  EXPECT_GE(within, 0.95);
  // Normals radial and outward.
  for (std::size_t i = 0; i < a.cloud.size(); ++i) ASSERT_GT(a.cloud.normals[i].dot(a.truth[i]), 0.99f) << i;
}

TEST(Curvature, NoisySphereWithinTenPercent) {
  const float r = 1.f;
  test::SampleSpec spec{.n = 20000, .seed = 11};
  spec.noise_sigma = 0.001f * test::diagonal(test::sphere(r, {.n = 1000}));
  const Analysed a = analyse(test::sphere(r, spec));
  const Curvature& c = a.surface.curvature;
  const double within = fraction(a.cloud.size(), kAll, [&](std::size_t i) {
    return std::abs(c.k1[i] * r - 1.f) < 0.10f && std::abs(c.k2[i] * r - 1.f) < 0.10f;
  });
  EXPECT_GE(within, 0.95) << "fit over " << c.fit_neighbours << " neighbours, noise " << c.noise_sigma;
  EXPECT_GT(c.fit_neighbours, a.surface.neighbourhoods.k);  // the noise was noticed
}

}  // namespace
}  // namespace pcsketch::differential
