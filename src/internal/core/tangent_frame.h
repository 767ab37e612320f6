#pragma once
// A tangent frame of a unit normal: the border test and the contours' bending test project neighbours onto it.

#include <Eigen/Geometry>
#include <cmath>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::detail {

/// Right-handed orthonormal tangent frame (u, v) of a unit normal.
inline void tangent_frame(const Vec3f& n, Vec3f& u, Vec3f& v) {
  u = (std::abs(n.x()) < 0.9f ? Vec3f::UnitX() : Vec3f::UnitY()).cross(n).normalized();
  v = n.cross(u);
}

}  // namespace pcsketch::detail
