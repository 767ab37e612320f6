#pragma once
// The per-point quadric fit of the curvature stage: a height field over a point and its neighbours, in the tangent
// frame of its normal.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::differential::detail {

/// Neighbours of the smaller fit that separates noise from shape misfit (the point itself makes 6 + 6 dof).
constexpr std::size_t kInnerFit = 11;

/// What a fit computes: the residual feeds the noise estimates, the shape the curvature (a wide fit needs no
/// residual: skipping its pass over the neighbours is a tenth of a noisy cloud's curvature time).
enum class Want { residual, shape, both };

/// Principal curvatures at one point (our sign convention) and the residual of the fit.
struct PointFit {
  float k1 = 0, k2 = 0;
  Vec3f dir1 = Vec3f::UnitX(), dir2 = Vec3f::UnitY();
  double residual = 0;  ///< RMS distance of the points to the fitted graph along the normal, dof-corrected
};

/// Least-squares quadric height field z = a x² + b xy + c y² + d x + e y + f over point i and its first `count`
/// neighbours, in the tangent frame of `normal`: principal curvatures from the shape operator of the fitted graph
/// at the origin, and the fit's residual, as `want` asks. With `inner`, also the residual of the fit over its first
/// kInnerFit ≤ count neighbours, from the same tangent-frame coordinates. No normal: a zero fit.
PointFit fit_point(const std::vector<Vec3f>& points, std::size_t i, const Vec3f& normal,
                   const std::uint32_t* neighbours, std::size_t count, double* inner, Want want);

}  // namespace pcsketch::differential::detail
