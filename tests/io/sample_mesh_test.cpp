#include "pcsketch/io/sample_mesh.h"

#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>

#include <cmath>

#include "pcsketch/core/error.h"

namespace pcsketch::io {
namespace {

// Two triangles in the plane z = 1 with areas 1 and 3 (1:3).
Mesh two_triangles() {
  Mesh m;
  m.vertices = {Vec3f(0, 0, 1), Vec3f(2, 0, 1), Vec3f(0, 1, 1), Vec3f(3, 0, 1), Vec3f(5, 0, 1), Vec3f(3, 3, 1)};
  m.faces = {{0, 1, 2}, {3, 4, 5}};
  return m;
}

TEST(SampleMesh, FaceCountsProportionalToArea) {
  const std::size_t n = 40000;
  const PointCloud c = sample_mesh(two_triangles(), {.n = n, .seed = 7});
  ASSERT_EQ(c.size(), n);
  std::size_t first = 0;
  for (const std::uint32_t f : c.source_index) first += f == 0;
  // Binomial(n, 1/4): standard deviation sqrt(n * 3/16) ≈ 87, 5 sigma ≈ 433.
  EXPECT_NEAR(double(first), n / 4.0, 433.0);
  EXPECT_FALSE(c.has_normals());
}

TEST(SampleMesh, SamplesLieInTheirTriangle) {
  const Mesh m = two_triangles();
  const PointCloud c = sample_mesh(m, {.n = 5000, .seed = 3, .keep_normals = true});
  ASSERT_TRUE(c.has_normals());
  for (std::size_t i = 0; i < c.size(); ++i) {
    const auto& f = m.faces[c.source_index[i]];
    const Vec3f a = m.vertices[f[0]], b = m.vertices[f[1]], d = m.vertices[f[2]];
    const Vec3f p = c.positions[i];
    EXPECT_FLOAT_EQ(p.z(), 1.f);
    // Barycentric sign test in the plane: p is on the inner side of every edge.
    const auto side = [](const Vec3f& u, const Vec3f& v, const Vec3f& q) {
      return (v.x() - u.x()) * (q.y() - u.y()) - (v.y() - u.y()) * (q.x() - u.x());
    };
    EXPECT_GE(side(a, b, p), -1e-5f);
    EXPECT_GE(side(b, d, p), -1e-5f);
    EXPECT_GE(side(d, a, p), -1e-5f);
    EXPECT_NEAR(c.normals[i].z(), 1.f, 1e-6f);
  }
}

TEST(SampleMesh, UniformWithinATriangle) {
  // The half of the triangle (0,0)-(2,0)-(0,1) with x < 1 holds 3/4 of its area.
  Mesh m = two_triangles();
  m.faces.resize(1);
  const PointCloud c = sample_mesh(m, {.n = 20000, .seed = 11});
  std::size_t left = 0;
  for (const Vec3f& p : c.positions) left += p.x() < 1.f;
  // Binomial sd = sqrt(20000 * 3/16) ≈ 61; 5 sigma.
  EXPECT_NEAR(double(left), 15000.0, 306.0);
}

TEST(SampleMesh, DeterministicPerSeedAndThreadCount) {
  const Mesh m = two_triangles();
  const SampleOptions o{.n = 50000, .noise_sigma_factor = 0.01, .seed = 5};
  const PointCloud a = sample_mesh(m, o);
  PointCloud b;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    b = sample_mesh(m, o);
  }
  EXPECT_EQ(a.positions, b.positions);
  SampleOptions other = o;
  other.seed = 6;
  EXPECT_NE(sample_mesh(m, other).positions, a.positions);
}

TEST(SampleMesh, NoiseIsAFractionOfTheDiagonal) {
  const Mesh m = two_triangles();
  const double diagonal = bounding_box(m.vertices).diagonal();
  const PointCloud c = sample_mesh(m, {.n = 20000, .noise_sigma_factor = 0.01, .seed = 9});
  double sum = 0, sum2 = 0;
  for (const Vec3f& p : c.positions) {
    sum += p.z() - 1.0;
    sum2 += (p.z() - 1.0) * (p.z() - 1.0);
  }
  const double mean = sum / double(c.size());
  const double sigma = std::sqrt(sum2 / double(c.size()) - mean * mean);
  EXPECT_NEAR(sigma, 0.01 * diagonal, 0.03 * 0.01 * diagonal);
  EXPECT_NEAR(mean, 0.0, 0.05 * 0.01 * diagonal);
}

TEST(SampleMesh, RejectsDegenerateInput) {
  Mesh m = two_triangles();
  EXPECT_THROW(sample_mesh(m, {.n = 0}), Error);
  m.faces = {{0, 0, 1}};
  EXPECT_THROW(sample_mesh(m, {.n = 10}), Error);
  m.faces = {{0, 1, 9}};
  EXPECT_THROW(sample_mesh(m, {.n = 10}), Error);
}

}  // namespace
}  // namespace pcsketch::io
