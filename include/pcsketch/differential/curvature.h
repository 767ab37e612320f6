#pragma once
// Principal curvatures by a least-squares quadric fit (the paper's reference [20]).

#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

struct CurvatureOptions {
  /// Neighbours used in the fit; 0 = all of the shared neighbourhood (its k).
  std::size_t k = 0;
  ProgressFn progress;  ///< optional
};

/// Sign convention: with outward normals, convex is positive (a sphere of radius R has k1 = k2 = +1/R).
struct Curvature {
  std::vector<float> k1;    ///< #P, maximum principal curvature, 1/model units
  std::vector<float> k2;    ///< #P, minimum principal curvature (k1 ≥ k2)
  std::vector<Vec3f> dir1;  ///< #P, unit principal direction of k1, tangent to the surface
  std::vector<Vec3f> dir2;  ///< #P, unit principal direction of k2 (= normal × dir1)
  Warnings warnings;

  float mean(std::size_t i) const { return 0.5f * (k1[i] + k2[i]); }
  float gaussian(std::size_t i) const { return k1[i] * k2[i]; }
};

/// Fits z = a x² + b xy + c y² + d x + e y + f to each point's neighbours in its tangent frame (oriented normals
/// required) and takes the principal curvatures of the fitted surface at the point.
Curvature estimate_curvature(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                             const neighbourhood::Neighbourhoods& neighbourhoods, const CurvatureOptions& options = {});

}  // namespace pcsketch::differential
