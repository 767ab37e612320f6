#pragma once
// Stray points of a scan (flying pixels, mixed pixels at depth edges, dust, a passing bird) found before any
// surface analysis, so that no later stage draws, frames or shades them (docs/geometry.md, "Outliers").

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::clean {

struct OutlierOptions {
  bool enabled = true;  ///< off: every point is surface (the paper's assumption)
  /// Neighbours of the distance statistic d_i, the mean distance to a point's k nearest (the first k of the shared
  /// neighbourhood). 8 sees past a pair or triple of duplicates.
  std::size_t k = 8;
  /// A point is dense when d_i ≤ density_factor × m, m the median of d over the cloud. A surface seen at a quarter
  /// of the median density has d ≈ 2 m, and scans overlapping at 4:1 stay well inside; stray points in the air are
  /// tens of m from anything.
  float density_factor = 4.0f;
  /// Dense points within link_factor × m of each other (k-NN pairs) are one cluster. A sparse point next to a
  /// dense one at that distance is its cluster's border (the thin edge of a scan), not an outlier.
  float link_factor = 4.0f;
  /// A point farther than max(offset_factor × m, 6 × the median offset) from the plane of its k nearest (PCA) is off
  /// the surface even where it is not sparse: a stray point a few spacings above a surface has that surface as its
  /// neighbours. A sharp corner's apex lies about 0.5 m off its neighbours' plane; 6 median offsets is 4σ of the
  /// offsets of a noisy surface, so noisy surfaces are not eroded.
  float offset_factor = 2.0f;
  /// A sparse point lies on a sheet when its nearest (the shared lists) spread in two dimensions round a plane, with at
  /// most this share of their variance across it, and it lies on that plane itself (within a quarter of its d_i). Such
  /// points are surface sampled more sparsely (a coarse mesh's large faces, a far part of a scan): they join each other
  /// and dense points at link_factor times the smaller of the two d, so a sparse region stays with the surface it
  /// continues. Stray points in the air spread in three dimensions (flying pixels along rays in one), and one near a
  /// surface lies off its neighbours' plane. 0: sparse points join only a dense neighbour, as a border.
  float sheet_variation = 0.04f;
  /// Clusters with fewer points than max(min_cluster, min_cluster_fraction × #P) are detached clumps (a spray of
  /// mixed pixels, a bird): left out.
  std::size_t min_cluster = 32;
  double min_cluster_fraction = 0.0005;
  ProgressFn progress;  ///< optional
};

struct OutlierResult {
  std::vector<std::uint8_t> outlier;  ///< #P, 1 for a point left out
  std::size_t isolated = 0;           ///< points off the surface, or sparse with no dense point or sheet near them
  std::size_t clustered = 0;          ///< points of clusters below the minimum size
  float median_distance = 0;          ///< m, model units
  std::size_t removed() const { return isolated + clustered; }
};

/// Finds the outliers of a cloud from its k-NN lists: points off the plane of their neighbours, points far sparser
/// than the cloud's median with no dense point near them and not on a sheet of sparse surface, and the points of
/// clusters (components of the k-NN graph over dense points) too small to be a surface. Linear in #P · k.
/// Deterministic.
/// @throws pcsketch::Error if the neighbourhoods do not match the points
OutlierResult find_outliers(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& neighbourhoods,
                            const OutlierOptions& options = {});

}  // namespace pcsketch::clean
