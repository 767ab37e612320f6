#pragma once
// Area-uniform random samples of a triangle mesh's surface: clouds of any size with known ground truth.

#include <cstddef>
#include <cstdint>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::io {

struct SampleOptions {
  std::size_t n = 100000;  ///< number of samples
  /// Standard deviation of the isotropic Gaussian noise added to each sample, as a fraction of the mesh's
  /// bounding-box diagonal (0.001 = 0.1% of the diagonal). 0: exactly on the surface.
  double noise_sigma_factor = 0.0;
  std::uint64_t seed = 1;  ///< same seed, same cloud, for any thread count
  /// Store each sample's face normal as its normal. Off by default: a raw scan has no normals, and the pipeline
  /// should be tested on what it gets in practice.
  bool keep_normals = false;
  /// Stray points added after the surface samples, as a fraction of n (0.01 = 1%): flying pixels and dust, uniform
  /// in the mesh's bounding box grown by 10% of its diagonal on every side. Their source_index is kOutlier.
  double outlier_fraction = 0.0;
  /// Outliers come in clumps of this many points (1: isolated), each clump a Gaussian blob of σ = 0.2% of the
  /// diagonal around a uniform centre: small detached clusters such as a scanned bird or a mixed-pixel spray.
  std::size_t outlier_clump = 1;
};

/// source_index of an outlier added by sample_mesh (no face).
inline constexpr std::uint32_t kOutlier = 0xffffffffu;

/// Samples `options.n` points uniformly by area: a face is chosen with probability proportional to its area (binary
/// search in the cumulative area table), a point in it with uniform barycentrics (u = 1 - sqrt(r1), v = r2 sqrt(r1)).
/// Points are generated in fixed chunks, each with its own seeded generator, so the result does not depend on the
/// number of threads. The cloud shares the mesh's origin; source_index holds the face of each sample (kOutlier for
/// the stray points of options.outlier_fraction, which follow the surface samples).
/// @throws pcsketch::Error if n is 0, the mesh has no face of positive area, or an index is out of range.
PointCloud sample_mesh(const Mesh& mesh, const SampleOptions& options = {});

}  // namespace pcsketch::io
