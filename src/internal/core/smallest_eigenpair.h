#pragma once
// The smallest eigenpair of a 3×3 covariance, for PCA normals, without Eigen's trigonometry.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

namespace pcsketch::detail {

/// The smallest eigenvalue of a symmetric positive semi-definite 3×3 `c` and its unit eigenvector, without the
/// trigonometry of Eigen's closed form (two thirds of its time, and its time was most of the normals'). The smallest
/// root of the characteristic cubic of c / trace(c) by Halley's iteration from e3/e2, which lies at or below it, then
/// the largest cross product of two rows of c − λ0·I, as Eigen's computeDirect takes it. False where λ0 is not
/// clearly apart from λ1 (ties, lines, a point): the caller asks Eigen then.
inline bool smallest_eigenpair(const Eigen::Matrix3d& c, double& lambda0, Eigen::Vector3d& vector) {
  constexpr double kApart = 1e-4;  // λ1 − λ0 over the trace: the cross products stay far from cancelling
  const double trace = c.trace();
  if (!(trace > 0) || !std::isfinite(trace)) return false;
  const Eigen::Matrix3d m = c / trace;
  const double a = m(0, 0), b = m(1, 1), d = m(2, 2), x = m(0, 1), y = m(0, 2), z = m(1, 2);
  const double e2 = a * b - x * x + a * d - y * y + b * d - z * z;  // the cubic λ³ − λ² + e2·λ − e3
  const double e3 = a * (b * d - z * z) - x * (x * d - z * y) + y * (x * z - b * y);
  if (!(e2 > 0)) return false;
  double l = std::max(0.0, e3 / e2);
  for (int iteration = 0; iteration < 16; ++iteration) {
    const double p = ((l - 1) * l + e2) * l - e3, dp = (3 * l - 2) * l + e2, ddp = 6 * l - 2;
    const double step = 2 * p * dp / (2 * dp * dp - p * ddp);
    if (!std::isfinite(step)) return false;
    l -= step;
    if (std::abs(step) <= 1e-15) break;
  }
  const double rest = 1 - l, root = std::sqrt(std::max(0.0, rest * rest - 4 * (e2 - l * rest)));
  if (!(0.5 * (rest - root) - l > kApart)) return false;
  Eigen::Matrix3d shifted = m;
  shifted.diagonal().array() -= l;
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  for (const auto& [r, s] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    const Eigen::Vector3d cross = shifted.row(r).transpose().cross(shifted.row(s).transpose());
    if (cross.squaredNorm() > best.squaredNorm()) best = cross;
  }
  lambda0 = std::max(0.0, l) * trace;
  vector = best.normalized();
  return true;
}

}  // namespace pcsketch::detail
