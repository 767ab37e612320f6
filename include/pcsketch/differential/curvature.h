#pragma once
// Principal curvatures by a least-squares quadric fit (the paper's reference [20]).

#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

struct CurvatureOptions {
  /// Neighbours used in the fit. 0 = automatic: the shared neighbourhood (its k), enlarged on noisy clouds when
  /// adapt_to_noise is set. A value above the shared k is served by kd-tree queries.
  std::size_t k = 0;
  /// With k = 0: estimate the noise σ from the residuals of first fits over the shared k and the nearest 11
  /// neighbours (separating noise from the shape's misfit) and refit over n ≥ 8·σ·√(πρ)/noise_tolerance neighbours
  /// (ρ the point density) when n > 1.25·k, the size at which the fit's curvature noise falls below
  /// noise_tolerance / r (r the fit radius). Clean clouds keep the shared k; see docs/geometry.md.
  bool adapt_to_noise = true;
  /// Target curvature noise relative to the curvature 1/r of the support radius r (dimensionless). The default
  /// keeps both principal curvatures within 10% at > 99% of the points of a 20k-point sphere with noise 0.1% of its
  /// diagonal (about 300 neighbours per fit there; the fit's bias is then ~1%).
  float noise_tolerance = 0.0065f;
  /// Upper bound on the automatic fit size (time grows linearly with it; memory only per thread).
  std::size_t max_k = 512;
  ProgressFn progress;  ///< optional
};

/// Sign convention: with outward normals, convex is positive (a sphere of radius R has k1 = k2 = +1/R).
struct Curvature {
  std::vector<float> k1;    ///< #P, maximum principal curvature, 1/model units
  std::vector<float> k2;    ///< #P, minimum principal curvature (k1 ≥ k2)
  std::vector<Vec3f> dir1;  ///< #P, unit principal direction of k1, tangent to the surface
  std::vector<Vec3f> dir2;  ///< #P, unit principal direction of k2 (= normal × dir1)
  std::size_t fit_neighbours = 0;  ///< neighbours used per fit (after noise adaptation)
  std::size_t point_fits = 0;  ///< wide fits only: points fitted one by one (creases: their own ball, or their shared
                               ///< neighbours in a denoised copy); the rest share their group's
  float noise_sigma = 0;           ///< noise σ̂, model units: noise share of the median first-fit residual
  Warnings warnings;

  float mean(std::size_t i) const { return 0.5f * (k1[i] + k2[i]); }
  float gaussian(std::size_t i) const { return k1[i] * k2[i]; }
};

/// A denoised copy of the cloud (differential::denoise), same points in the same order. Where a wide fit's support
/// holds a crease, its points are fitted over their shared k neighbours in this copy, whose creases the denoising
/// kept sharp, instead of over their own wide ball of the noisy points (docs/geometry.md, "Noise", item 8).
struct DenoisedCopy {
  const std::vector<Vec3f>* points = nullptr;   ///< #P moved positions; null: no copy
  const std::vector<Vec3f>* normals = nullptr;  ///< #P their unit normals, oriented as the fit's normals
};

/// Fits z = a x² + b xy + c y² + d x + e y + f (unweighted least squares, the point itself included) to each point's
/// neighbours in its tangent frame (oriented normals required) and takes the principal curvatures of the fitted
/// graph at the origin from its shape operator I⁻¹·II, so a tilted normal (d, e ≠ 0) does not bias them.
/// Underdetermined or degenerate fits (fewer than 6 points, collinear neighbours) get the minimum-norm solution of a
/// slightly regularised system: curvature 0 in the directions the data do not see, never NaN.
/// @param points       #P positions
/// @param normals      #P unit normals, consistently oriented (outward for the sign convention)
/// @param neighbourhoods  the shared k-NN of `points`
/// @param tree         kd-tree over `points`, used when the fit needs more neighbours than the shared k
/// @param denoised     optional: the denoised copy whose shared-k fits replace the per-point wide fits at creases
/// @throws pcsketch::Error if the sizes disagree
Curvature estimate_curvature(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                             const neighbourhood::Neighbourhoods& neighbourhoods, const neighbourhood::KdTree& tree,
                             const CurvatureOptions& options = {}, const DenoisedCopy& denoised = {});
/// The noise σ̂ the curvature step estimates (see CurvatureOptions::adapt_to_noise), model units, from the fits at
/// no more than `max_samples` points spread along the point order (space-filling-curve order spreads them over the
/// surface). Cheap enough to decide, before any other work, whether a cloud needs denoising.
/// @param normals #P unit normals; their signs do not matter
float estimate_noise(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                     const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t max_samples = 16384);

/// Share of the shared-k fits' squared residual that does not grow when the fit widens to 40 neighbours (the
/// nearest of the neighbours' neighbours): noise stays the same at any fit size, the misfit of a shape sampled too
/// coarsely for a quadric grows as the cube of the fit size. 1 on pure noise, near 0 on a coarse mesh's vertices.
float noise_share(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                  const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t max_samples = 4096);

/// As above; builds a kd-tree only if the fit needs more neighbours than the shared k.
Curvature estimate_curvature(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                             const neighbourhood::Neighbourhoods& neighbourhoods, const CurvatureOptions& options = {});

}  // namespace pcsketch::differential
