#include "support/analytic_shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace pcsketch::test {

namespace {

constexpr float kPi = 3.14159265358979f;

/// Draws points from `gen(rng, position, normal)` (which may reject by returning false) and adds noise.
template <class Gen>
PointCloud generate(const SampleSpec& spec, Gen gen) {
  std::mt19937 rng(spec.seed);
  std::normal_distribution<float> noise(0.f, 1.f);
  PointCloud cloud;
  cloud.positions.reserve(spec.n);
  cloud.normals.reserve(spec.n);
  while (cloud.positions.size() < spec.n) {
    Vec3f p, nrm;
    if (!gen(rng, p, nrm)) continue;
    if (spec.noise_sigma > 0) p += spec.noise_sigma * Vec3f(noise(rng), noise(rng), noise(rng));
    cloud.positions.push_back(p);
    cloud.normals.push_back(nrm.normalized());
  }
  return cloud;
}

float uniform(std::mt19937& rng, float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }

}  // namespace

PointCloud sphere(float r, const SampleSpec& spec, const Vec3f& center) {
  return generate(spec, [&](std::mt19937& rng, Vec3f& p, Vec3f& n) {
    std::normal_distribution<float> g(0.f, 1.f);
    n = Vec3f(g(rng), g(rng), g(rng));
    if (n.norm() < 1e-6f) return false;
    n.normalize();
    p = center + r * n;
    return true;
  });
}

PointCloud cylinder(float r, float h, const SampleSpec& spec) {
  return generate(spec, [&](std::mt19937& rng, Vec3f& p, Vec3f& n) {
    const float t = uniform(rng, 0.f, 2 * kPi);
    n = Vec3f(std::cos(t), std::sin(t), 0.f);
    p = Vec3f(r * n.x(), r * n.y(), uniform(rng, -h / 2, h / 2));
    return true;
  });
}

PointCloud torus(float R, float r, const SampleSpec& spec) {
  return generate(spec, [&](std::mt19937& rng, Vec3f& p, Vec3f& n) {
    const float u = uniform(rng, 0.f, 2 * kPi), v = uniform(rng, 0.f, 2 * kPi);
    // Area element is proportional to R + r cos v: reject to make the sampling area-uniform.
    if (uniform(rng, 0.f, R + r) > R + r * std::cos(v)) return false;
    n = Vec3f(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
    p = Vec3f((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    return true;
  });
}

PointCloud plane(float a, const SampleSpec& spec) {
  return generate(spec, [&](std::mt19937& rng, Vec3f& p, Vec3f& n) {
    p = Vec3f(uniform(rng, -a, a), uniform(rng, -a, a), 0.f);
    n = Vec3f::UnitZ();
    return true;
  });
}

PointCloud saddle(float a, const SampleSpec& spec) {
  const float max_element = std::sqrt(1.f + 8.f * a * a);
  return generate(spec, [&](std::mt19937& rng, Vec3f& p, Vec3f& n) {
    const float x = uniform(rng, -a, a), y = uniform(rng, -a, a);
    const float element = std::sqrt(1.f + 4.f * x * x + 4.f * y * y);
    if (uniform(rng, 0.f, max_element) > element) return false;
    p = Vec3f(x, y, x * x - y * y);
    n = Vec3f(-2.f * x, 2.f * y, 1.f);
    return true;
  });
}

namespace {

// Adds the rectangle with corners p, p+u, p+u+v, p+v as two triangles.
void add_rectangle(Mesh& mesh, const Vec3f& p, const Vec3f& u, const Vec3f& v) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), {p, p + u, p + u + v, p + v});
  mesh.faces.push_back({base, base + 1, base + 2});
  mesh.faces.push_back({base, base + 2, base + 3});
}

}  // namespace

Mesh notched_box() {
  const float Y = 0.8f, bottom = -0.6f, top = 0.6f, w = 0.3f, d = 0.4f, floor = top - d;
  Mesh mesh;
  const Vec3f ey(0, 2 * Y, 0);
  const auto rect_xz = [&](float x0, float x1, float z0, float z1) {  // profile rectangle, both caps
    add_rectangle(mesh, {x0, -Y, z0}, {x1 - x0, 0, 0}, {0, 0, z1 - z0});
    add_rectangle(mesh, {x0, Y, z0}, {x1 - x0, 0, 0}, {0, 0, z1 - z0});
  };
  rect_xz(-1, -w, bottom, top);
  rect_xz(-w, w, bottom, floor);
  rect_xz(w, 1, bottom, top);
  add_rectangle(mesh, {-1, -Y, bottom}, {2, 0, 0}, ey);             // bottom
  add_rectangle(mesh, {-1, -Y, bottom}, {0, 0, top - bottom}, ey);  // x = -1
  add_rectangle(mesh, {1, -Y, bottom}, {0, 0, top - bottom}, ey);   // x = +1
  add_rectangle(mesh, {-1, -Y, top}, {1 - w, 0, 0}, ey);            // top, left of the notch
  add_rectangle(mesh, {w, -Y, top}, {1 - w, 0, 0}, ey);             // top, right of the notch
  add_rectangle(mesh, {-w, -Y, floor}, {0, 0, d}, ey);              // notch walls
  add_rectangle(mesh, {w, -Y, floor}, {0, 0, d}, ey);
  add_rectangle(mesh, {-w, -Y, floor}, {2 * w, 0, 0}, ey);          // notch floor
  return mesh;
}

Mesh box(const Vec3f& half) {
  Mesh mesh;
  for (std::uint32_t i = 0; i < 8; ++i)
    mesh.vertices.emplace_back(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(),
                               i & 4 ? half.z() : -half.z());
  for (int axis = 0; axis < 3; ++axis)
    for (const std::uint32_t side : {0u, 1u}) {
      const std::uint32_t k = 1u << axis, u = 1u << (axis + 1) % 3, v = 1u << (axis + 2) % 3;
      const std::uint32_t base = side ? k : 0;
      // Counter-clockwise around +axis (u × v = axis), reversed on the negative side.
      std::array<std::uint32_t, 4> quad{base, base | u, base | u | v, base | v};
      if (!side) std::reverse(quad.begin(), quad.end());
      mesh.faces.push_back({quad[0], quad[1], quad[2]});
      mesh.faces.push_back({quad[0], quad[2], quad[3]});
    }
  return mesh;
}

PointCloud cube(float a, const SampleSpec& spec) {
  return generate(spec, [&](std::mt19937& rng, Vec3f& p, Vec3f& n) {
    const int face = std::uniform_int_distribution<int>(0, 5)(rng);
    const int axis = face / 2;
    const float sign = face % 2 ? 1.f : -1.f;
    p = Vec3f(uniform(rng, -a, a), uniform(rng, -a, a), uniform(rng, -a, a));
    p[axis] = sign * a;
    n = Vec3f::Zero();
    n[axis] = sign;
    return true;
  });
}

float diagonal(const PointCloud& cloud) { return bounding_box(cloud.positions).diagonal(); }

void add_outliers(PointCloud& cloud, float fraction, std::size_t clump, std::uint32_t seed) {
  const Box3f box = bounding_box(cloud.positions);
  const float d = box.diagonal();
  const std::size_t n = cloud.size();
  cloud.source_index.resize(n);
  for (std::size_t i = 0; i < n; ++i) cloud.source_index[i] = static_cast<std::uint32_t>(i);
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.f, 1.f);
  const auto count = static_cast<std::size_t>(std::lround(fraction * static_cast<float>(n)));
  Vec3f centre = Vec3f::Zero();
  for (std::size_t j = 0; j < count; ++j) {
    if (j % clump == 0)
      for (int a = 0; a < 3; ++a) centre[a] = uniform(rng, box.min[a] - 0.1f * d, box.max[a] + 0.1f * d);
    const Vec3f p = clump > 1 ? Vec3f(centre + 0.002f * d * Vec3f(g(rng), g(rng), g(rng))) : centre;
    cloud.positions.push_back(p);
    cloud.source_index.push_back(kOutlier);
    if (!cloud.normals.empty()) cloud.normals.push_back(Vec3f::UnitZ());
  }
}

}  // namespace pcsketch::test
