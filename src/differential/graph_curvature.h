#pragma once
// Principal curvatures of a height field z = h(x, y) over a tangent frame, shared by the per-point quadric fits and
// the group fits of noisy clouds.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::differential::detail {

/// Right-handed orthonormal tangent frame (u, v) of a unit normal, branch-free (Duff et al. 2017).
inline void tangent_frame(const Vec3d& n, Vec3d& u, Vec3d& v) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  u = Vec3d(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  v = Vec3d(b, sign + n.y() * n.y() * a, -n.y());
}

/// Principal curvatures (our sign: convex towards the frame's normal is positive, k1 ≥ k2) and the frame
/// coordinates (ξ, η) of k1's direction; xi is zero at an umbilic (every direction is principal).
struct GraphCurvature {
  double k1 = 0, k2 = 0;
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
};

/// From the derivatives of h at the point (model units): the eigenvalues of the shape operator I⁻¹·II of the graph,
/// so a tilted frame (h_x, h_y ≠ 0) does not bias them.
inline GraphCurvature graph_curvature(double hx, double hy, double hxx, double hxy, double hyy) {
  const double e = 1 + hx * hx, f = hx * hy, g = 1 + hy * hy;
  const double w = std::sqrt(1 + hx * hx + hy * hy);
  const double l = hxx / w, m = hxy / w, nn = hyy / w;
  // Eigenvalues of I⁻¹·II (curvatures towards +normal) from det(II − κ I) = 0; det I = w².
  const double h = (l * g - 2 * m * f + nn * e) / (2 * w * w);
  const double gauss = (l * nn - m * m) / (w * w);
  const double root = std::sqrt(std::max(0.0, h * h - gauss));
  const double toward_min = h - root;
  GraphCurvature out;
  // Convex (bending away from an outward normal) is positive: negate, so k1 = −min, k2 = −max.
  out.k1 = -toward_min;
  out.k2 = -(h + root);
  // Eigenvector of toward_min: a row of (II − κ I) is orthogonal to it; take the better conditioned one.
  const Eigen::Vector2d a(m - toward_min * f, -(l - toward_min * e));
  const Eigen::Vector2d b(nn - toward_min * g, -(m - toward_min * f));
  const Eigen::Vector2d xi = a.squaredNorm() >= b.squaredNorm() ? a : b;
  if (xi.squaredNorm() > 1e-24 * (l * l + m * m + nn * nn) && xi.squaredNorm() > 0) out.xi = xi;
  return out;
}

}  // namespace pcsketch::differential::detail
