#pragma once
// Feature-preserving denoising of a scanned cloud: bilateral filtering of the PCA normals, then each point moved onto
// the tangent planes of its neighbours whose filtered normals agree with its own (docs/geometry.md, "Noise"). Runs
// only when the estimated noise is a visible fraction of the spacing, so clean clouds are left exactly as they are.
// Where many PCA normals lie beyond the filter's reach (noise near half their radius), they are taken over 64
// neighbours instead ("Noise", item 9).

#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

struct DenoiseOptions {
  /// Denoise when the estimated noise σ̂ (estimate_noise) exceeds min_noise_factor · h. Off: the paper's raw cloud.
  bool enabled = true;
  /// The noise level that triggers denoising, in units of the mean spacing h. Clean samples of the shared meshes
  /// estimate σ̂ < 0.01 h; Gaussian noise of 0.1% of the diagonal on 200k points is about 0.6 h. Below 0.25 h
  /// denoising costs more than it buys: on 200k samples of bunny, camel and fandisk with σ̂ = 0.13–0.22 h the raw
  /// cloud's contours score at most 0.04 below the denoised ones (and up to 0.06 above); on sparse clouds (8k–20k
  /// noisy samples, a rough mesh's vertices) its moves span pixels and the raw cloud draws far better (contour F1
  /// up to +0.25). From 0.25 h on denoising wins: contour precision raw 0.88–0.99 against 0.99–1.00 at 0.24–0.31 h,
  /// 0.74–0.83 against 0.98–1.00 at 0.37–0.46 h. docs/geometry.md, "Noise".
  float min_noise_factor = 0.25f;
  /// Rounds of (PCA normals, bilateral normal filter, point update). Each round averages the heights of about k
  /// neighbours, so the noise falls roughly as 1/√(k · rounds); 3 rounds bring 0.4 h to under 0.1 h.
  std::size_t iterations = 3;
  /// Bilateral normal filtering passes per round: each averages a normal with its k neighbours', weighted by
  /// distance and by normal similarity.
  std::size_t normal_passes = 2;
  /// Cutoff c of the normal-similarity weight, Tukey's biweight (1 − (t/c)²)² of t = 1 − |n_i·n_j| (0 from t = c),
  /// dimensionless. 0.15 keeps the weight above 0.99 for 8° of noise, halves it at 25° and zeroes it from 32° on:
  /// the planes on either side of a crease do not average, so edges stay sharp.
  float normal_cutoff = 0.15f;
  ProgressFn progress;  ///< optional
};

struct DenoiseResult {
  bool applied = false;          ///< the estimated noise exceeded the trigger and the points were moved
  bool noise_estimated = false;  ///< σ̂ was estimated (denoising on, k ≥ 6, spacing > 0); noise_before is 0 if not
  float noise_before = 0;        ///< σ̂ of the input, model units
  std::vector<Vec3f> normals;    ///< #P filtered unit normals of the moved points (unoriented); empty unless applied
  std::size_t iterations = 0;    ///< rounds run
};

/// Estimates the noise and, when it exceeds the trigger, moves `points` in place and refreshes the distances (and
/// their order) of `neighbourhoods` for the moved points. The neighbour sets are kept: points move by about σ, far
/// less than a neighbourhood's radius.
/// @param spacing mean spacing h of `points`, model units (> 0)
/// @param normals #P unit normals of the input (PCA or the file's; signs do not matter), for the noise estimate
/// @throws pcsketch::Error if the neighbourhoods or normals do not match the points
DenoiseResult denoise(std::vector<Vec3f>& points, neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                      const std::vector<Vec3f>& normals, const DenoiseOptions& options = {});

}  // namespace pcsketch::differential
