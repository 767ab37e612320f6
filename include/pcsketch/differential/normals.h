#pragma once
// Normals by PCA of each point's neighbourhood.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

struct NormalOptions {
  /// Neighbours used for the PCA; 0 = all of the shared neighbourhood (its k).
  std::size_t k = 0;
  ProgressFn progress;  ///< optional
};

struct NormalResult {
  std::vector<Vec3f> normals;          ///< #P, unit, unoriented (sign arbitrary until orient_normals)
  std::vector<float> surface_variation;  ///< #P, λ0/(λ0+λ1+λ2) in [0, 1/3]: 0 on a plane, large at edges and noise
  /// Points whose list holds two faces of a thin part, their normal taken over their own face (ascending).
  std::vector<std::uint32_t> own_face;
  Warnings warnings;
};

/// PCA normal of each point: eigenvector of the smallest eigenvalue of its neighbourhood's covariance. Where sorted
/// lists (with distances) reach a thin part's other face, the PCA is taken over the point's own face and the point
/// is listed in NormalResult::own_face (docs/geometry.md, "Thin parts"). Degenerate neighbourhoods (all identical,
/// collinear) get an arbitrary unit normal perpendicular to the data and a warning counting them; never NaN.
NormalResult estimate_normals(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& neighbourhoods,
                              const NormalOptions& options = {});

/// Angular noise of unit normals, radians: the median over points (at most `max_samples`, spread along the point
/// order) of the angle between a normal and the mean of its 8 nearest neighbours' (signs aligned). The surface's
/// bending tilts the neighbours' normals symmetrically and cancels in their mean, so a clean smooth cloud gives
/// nearly 0 and noise of δ per normal gives about δ.
float normal_noise(const std::vector<Vec3f>& normals, const neighbourhood::Neighbourhoods& neighbourhoods,
                   std::size_t max_samples = 16384);

}  // namespace pcsketch::differential
