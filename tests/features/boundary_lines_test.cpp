// Known answers of the border stage: closed shapes have no border, an open sheet's edge and a hole's rim are traced
// where they are, a small hole is found but not drawn, and density changes are no border.

#include "pcsketch/features/boundary_lines.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "pcsketch/core/error.h"
#include "pcsketch/differential/surface.h"
#include "support/analytic_shapes.h"

namespace pcsketch::features {
namespace {

constexpr float kPi = 3.14159265f;

struct Analysed {
  PointCloud cloud;
  differential::Surface surface;
  Boundary boundary;
};

Analysed analyse(PointCloud cloud, const BoundaryOptions& options = {}) {
  cloud.normals.clear();
  Analysed a{std::move(cloud), {}, {}};
  a.surface = differential::analyse_surface(a.cloud);
  a.boundary = find_boundaries(a.cloud.positions, a.cloud.normals, a.surface.neighbourhoods, a.surface.spacing, options);
  return a;
}

/// Keeps the points `keep` accepts (positions and their normals).
PointCloud filtered(const PointCloud& cloud, const std::function<bool(const Vec3f&)>& keep) {
  PointCloud out;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (keep(cloud.positions[i])) {
      out.positions.push_back(cloud.positions[i]);
      if (cloud.has_normals()) out.normals.push_back(cloud.normals[i]);
    }
  return out;
}

/// Bands of width 1/3 along x, alternately at full density and at a quarter of it (4:1, as where scans overlap).
PointCloud density_bands(const PointCloud& cloud, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  return filtered(cloud, [&](const Vec3f& p) {
    const bool sparse = static_cast<int>(std::floor(3.f * p.x())) % 2 != 0;
    return !sparse || u(rng) < 0.25f;
  });
}

/// Fraction of `truth` (points along a border) within `tolerance` of some vertex of the lines.
double covered(const std::vector<Vec3f>& truth, const std::vector<Polyline>& lines, float tolerance) {
  std::size_t hit = 0;
  for (const Vec3f& t : truth) {
    bool near = false;
    for (const Polyline& l : lines)
      for (const Vec3f& p : l.points) near = near || (p - t).norm() <= tolerance;
    hit += near;
  }
  return static_cast<double>(hit) / static_cast<double>(truth.size());
}

std::vector<Vec3f> circle(const Vec3f& centre, float radius, std::size_t count) {
  std::vector<Vec3f> out;
  for (std::size_t i = 0; i < count; ++i) {
    const float t = 2 * kPi * static_cast<float>(i) / static_cast<float>(count);
    out.push_back(centre + radius * Vec3f(std::cos(t), std::sin(t), 0.f));
  }
  return out;
}

TEST(Boundary, ClosedShapesHaveNone) {
  const float sigma = 0.001f * 2.f * std::sqrt(3.f);
  for (const PointCloud& cloud :
       {test::sphere(1.f, {.n = 20000, .seed = 1}), test::cube(1.f, {.n = 20000, .seed = 2}),
        test::torus(1.f, 0.3f, {.n = 20000, .seed = 3}), test::cube(1.f, {.n = 30000, .seed = 4, .noise_sigma = sigma}),
        density_bands(test::sphere(1.f, {.n = 60000, .seed = 5}), 5)}) {
    const Analysed a = analyse(cloud);
    EXPECT_TRUE(a.boundary.lines.empty()) << a.boundary.lines.size() << " lines";
    EXPECT_EQ(a.boundary.border_points, 0u);
    // Whatever the confirmation leaves (a spot of the random sampling) is tiny.
    EXPECT_LT(std::count(a.boundary.border.begin(), a.boundary.border.end(), 1), 20);
  }
}

TEST(Boundary, SheetEdgeAndHoleRimTracedSmallHoleNot) {
  const Vec3f big(0.4f, 0.3f, 0.f), small(-0.4f, -0.4f, 0.f);
  // About 28 h and 3 h: a hole narrower than the confirmation's cone (about 14 h) is no border.
  const float big_radius = 0.2f, small_radius = 0.02f;
  const PointCloud sheet = filtered(test::plane(1.f, {.n = 20000, .seed = 6}), [&](const Vec3f& p) {
    return (p - big).norm() > big_radius && (p - small).norm() > small_radius;
  });
  const Analysed a = analyse(sheet);
  const float h = a.surface.spacing;
  ASSERT_FALSE(a.boundary.lines.empty());
  std::size_t vertices = 0, close = 0;
  for (const Polyline& line : a.boundary.lines) {
    EXPECT_EQ(line.kind, LineKind::Boundary);
    for (const Vec3f& p : line.points) {
      const float to_edge = 1.f - p.head<2>().cwiseAbs().maxCoeff();
      const float off = std::min(to_edge, std::abs((p - big).norm() - big_radius));
      EXPECT_LT(off, 6 * h) << "a border vertex at " << p.transpose();
      EXPECT_GT((p - small).norm(), small_radius + 4 * h) << "the small hole was drawn";
      ++vertices, close += off < 2.5f * h;
    }
  }
  // The lines run along the last row of points, about h inside the edge; where the sampling leaves a gap in that
  // row, a line may cut up to 5h inside.
  EXPECT_GE(static_cast<double>(close), 0.95 * static_cast<double>(vertices));
  std::vector<Vec3f> edge;
  for (int i = 0; i < 200; ++i) {
    const float t = -0.95f + 1.9f * static_cast<float>(i) / 199.f;  // corners left out: lines stop at corners
    for (const Vec3f& e : {Vec3f(t, -1, 0), Vec3f(t, 1, 0), Vec3f(-1, t, 0), Vec3f(1, t, 0)}) edge.push_back(e);
  }
  // The traced line runs along the middle of the band of border points, about h inside.
  EXPECT_GE(covered(edge, a.boundary.lines, 3 * h), 0.9);
  EXPECT_GE(covered(circle(big, big_radius, 200), a.boundary.lines, 3 * h), 0.9);
}

TEST(Boundary, DensityBandsAreNoBorder) {
  // An open sheet with 4:1 bands: the border is its edge only, not where the density changes.
  const Analysed a = analyse(density_bands(test::plane(1.f, {.n = 40000, .seed = 7}), 7));
  const float h = a.surface.spacing;
  for (std::size_t i = 0; i < a.cloud.size(); ++i)
    if (a.boundary.border[i] == Boundary::kDrawnRim || a.boundary.border[i] == Boundary::kUndrawnRim) {
      const float to_edge = 1.f - a.cloud.positions[i].head<2>().cwiseAbs().maxCoeff();
      // h is the mean over both densities: the sparse bands' spacing is about 1.6 h, their edge band as wide.
      EXPECT_LT(to_edge, 8 * h) << "a border point inside the sheet at " << a.cloud.positions[i].transpose();
    }
}

TEST(Boundary, OffFindsNothingAndOptionsAreChecked) {
  const PointCloud sheet = test::plane(1.f, {.n = 5000, .seed = 8});
  const Analysed a = analyse(sheet, {.enabled = false});
  EXPECT_TRUE(a.boundary.border.empty());
  EXPECT_TRUE(a.boundary.lines.empty());
  EXPECT_THROW(find_boundaries(a.cloud.positions, a.cloud.normals, a.surface.neighbourhoods, a.surface.spacing,
                               {.gap_threshold_deg = std::nanf("")}),
               Error);
  EXPECT_THROW(find_boundaries(a.cloud.positions, {}, a.surface.neighbourhoods, a.surface.spacing), Error);
}

}  // namespace
}  // namespace pcsketch::features
