#pragma once
// Ridge and valley points: the detection step of the paper's §IV.A.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/differential/curvature.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::features {

/// Per-point label; the numeric values are the ones written to PLY files (`label` property).
enum class PointLabel : std::uint8_t { None = 0, Ridge = 1, Valley = 2 };

/// Which test a point must pass to be a ridge/valley point.
enum class DetectionRule : std::uint8_t {
  /// The paper's rule alone: signed curvature beyond α times the extreme of its side. Marks every point of a sphere or
  /// a cylinder (uniform curvature) and every noise bump whose curvature reaches α times the extreme.
  Paper,
  /// The paper's rule, plus what separates an edge from a curved or noisy surface: an absolute floor relative to 1/h,
  /// a floor relative to the median |curvature| of the cloud, and non-maximum suppression along the principal
  /// direction (the point must be a local extremum of its curvature across the ridge). Default.
  Salient,
};

/// What "the extreme convex/concave curvature" of the paper's rule is.
enum class CurvatureExtreme : std::uint8_t {
  Percentile,  ///< a high percentile of the curvatures on each side: one outlier cannot move it. Default.
  MinMax,      ///< the paper's global maximum/minimum: exact paper behaviour, fragile under noise and outliers.
};

struct DetectionOptions {
  /// Paper's α (0 < α < 1): a point is a ridge point when its curvature k_i > 0 and k_i ≥ α·(extreme convex
  /// curvature); a valley point when k_i < 0 and |k_i| ≥ α·|extreme concave curvature|. Smaller α, more points (paper
  /// Fig. 3: 0.2, 0.1, 0.09). 0.2 is the paper's sparsest setting: with the robust extreme it keeps sharp edges and
  /// strong creases and drops gentle bends.
  float ridge_threshold_alpha = 0.2f;
  /// How the extreme curvature of each side is taken (see CurvatureExtreme).
  CurvatureExtreme extreme = CurvatureExtreme::Percentile;
  /// Percentile (0–100) of k_i among the points of one side used as that side's extreme when extreme = Percentile.
  /// 99: above the bulk of any sharp edge's curvature, below the 1% of estimates spoiled by noise, corners, outliers.
  float extreme_percentile = 99.f;
  /// Which rule (see DetectionRule).
  DetectionRule rule = DetectionRule::Salient;
  /// Salient rule: |k_i|·h must reach this (h = mean spacing): a bend whose radius of curvature is larger than
  /// h/0.065 ≈ 15h is resolved by the sampling as a smooth surface, not an edge. Dimensionless. 0.065 sits above the
  /// 99.9th percentile of |k|·h that Gaussian noise of σ = h/4 gives a flat face with the default 16-neighbour quadric
  /// fit, and below the curvature of most points within 1.5h of a sharp edge under that noise (measured on the cube).
  float saliency_floor = 0.065f;
  /// Salient rule: |k_i| must reach this many times the median |k_i| of the whole cloud. On a surface of uniform
  /// curvature (sphere, cylinder) every point sits at the median, and estimates scatter far less than a factor 2
  /// around it. 2 rather than more: on a scanned organic model (bunny.off) 4 left only 10 lines, 2 gives 24.
  float median_factor = 2.f;
  /// Salient rule: keep only points whose |k_i| is not exceeded by any neighbour lying within `suppression_cone_deg`
  /// of the principal direction of k_i (non-maximum suppression across the ridge), neither by one of the same sign nor
  /// by one of the opposite sign that passes its own side's thresholds: thins the band of high curvature around an
  /// edge to its crest, removes the plateaux of uniformly curved surfaces, and removes the weaker lobe of the other
  /// sign that the quadric fit puts beside a sharp edge (a valley line 1–2h off a convex edge).
  bool non_maximum_suppression = true;
  /// Half-angle (degrees) of the double cone around the principal direction in which neighbours compete in the
  /// non-maximum suppression. 30°: only neighbours clearly across the ridge compete; neighbours along the ridge or
  /// diagonal to it do not, so the crest keeps about one point per h or two of its length.
  float suppression_cone_deg = 30.f;
};

/// Statistics and per-point results of the detection.
struct DetectionResult {
  std::vector<PointLabel> labels;  ///< #P
  /// #P: k_i, the signed principal curvature of larger magnitude (k1 if |k1| ≥ |k2|, else k2), 1/model units,
  /// convex positive (the curvature the paper's rule is applied to).
  std::vector<float> feature_curvature;
  float convex_extreme = 0;    ///< extreme convex k_i used by the rule (≥ 0)
  float concave_extreme = 0;   ///< extreme concave k_i used by the rule (≤ 0)
  float ridge_threshold = 0;   ///< smallest k_i a ridge point has: the largest of every active floor (≥ 0)
  float valley_threshold = 0;  ///< largest k_i a valley point has (≤ 0)
  std::size_t ridge_points = 0;
  std::size_t valley_points = 0;
};

/// k_i of point i: the signed principal curvature of larger magnitude, and its principal direction.
float feature_curvature(const differential::Curvature& curvature, std::size_t i);
const Vec3f& feature_direction(const differential::Curvature& curvature, std::size_t i);

/// Labels every point as ridge, valley or none (paper §IV.A, first step). Parallel over points; the same output for
/// any number of threads.
/// @param[in] points #P positions
/// @param[in] curvature #P principal curvatures and directions (convex positive with outward normals)
/// @param[in] neighbourhoods k-NN of every point (used by the non-maximum suppression)
/// @param[in] spacing mean spacing h, model units (used by the saliency floor)
/// @param[in] progress optional, reports "ridge/valley detection" (a parameter, as for trace_lines)
/// @throws pcsketch::Error if the array sizes differ or an option is out of range.
DetectionResult detect_ridge_valley_points(const std::vector<Vec3f>& points, const differential::Curvature& curvature,
                                           const neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                                           const DetectionOptions& options = {}, const ProgressFn& progress = {});

}  // namespace pcsketch::features
