#pragma once
// Area-uniform samples of analytic surfaces with exact normals, for known-answer tests. Deterministic per seed.

#include <cstdint>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::test {

/// Options shared by every generator.
struct SampleSpec {
  std::size_t n = 20000;       ///< number of points
  std::uint32_t seed = 42;     ///< std::mt19937 seed
  float noise_sigma = 0.f;     ///< isotropic Gaussian noise, absolute model units
};

/// Sphere of radius r centred at `center`; normals radial outward. Curvatures: k1 = k2 = 1/r.
PointCloud sphere(float r, const SampleSpec& spec = {}, const Vec3f& center = Vec3f::Zero());
/// Side of a cylinder around the z axis, radius r, z in [-h/2, h/2]; normals outward. k1 = 1/r, k2 = 0.
PointCloud cylinder(float r, float h, const SampleSpec& spec = {});
/// Torus around the z axis: tube radius r at distance R from the axis; normals outward.
PointCloud torus(float R, float r, const SampleSpec& spec = {});
/// Square [-a, a]² in the plane z = 0; normals +z.
PointCloud plane(float a, const SampleSpec& spec = {});
/// Saddle z = x² − y² over [-a, a]²; normals on the +z side. At the origin k1 = 2, k2 = −2.
PointCloud saddle(float a, const SampleSpec& spec = {});
/// Surface of the axis-aligned cube [-a, a]³; normals are the face normals.
PointCloud cube(float a, const SampleSpec& spec = {});
/// Box [-1,1]×[-0.8,0.8]×[-0.6,0.6] with a notch x ∈ [-0.3,0.3], z ∈ [0.2, 0.6] cut across the top face along y,
/// as triangles: sharp convex edges (the rims) and concave ones (the notch's inner edges).
Mesh notched_box();
/// Axis-aligned box [-half, half] as 12 triangles on 8 shared vertices, wound with outward normals; vertex i has
/// coordinate axis k at +half[k] when bit k is set.
Mesh box(const Vec3f& half);
/// Diagonal of the bounding box of a cloud (for noise relative to the diagonal).
float diagonal(const PointCloud& cloud);

/// source_index of the points add_outliers appends.
inline constexpr std::uint32_t kOutlier = 0xffffffffu;
/// Appends fraction · #P stray points to `cloud`, uniform in its bounding box grown by 10% of the diagonal on every
/// side, in clumps of `clump` points (1: isolated; else Gaussian blobs of σ = 0.2% of the diagonal). The surface
/// points get source_index 0..#P−1, the stray ones kOutlier; normals (if any) of stray points are +z.
void add_outliers(PointCloud& cloud, float fraction, std::size_t clump = 1, std::uint32_t seed = 99);

}  // namespace pcsketch::test
