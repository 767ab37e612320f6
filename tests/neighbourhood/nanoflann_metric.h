#pragma once
// The squared distance exactly as nanoflann's L2_Simple_Adaptor evaluates it, for brute-force references.

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::neighbourhood {

/// Query minus point, squared and summed over x, y, z in this order, in float.
inline float distance_sq(const Vec3f& q, const Vec3f& p) {
  float result = 0;
  for (int d = 0; d < 3; ++d) {
    const float diff = q[d] - p[d];
    result += diff * diff;
  }
  return result;
}

}  // namespace pcsketch::neighbourhood
