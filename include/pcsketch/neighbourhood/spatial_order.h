#pragma once
// Scans arrive in random order; neighbours far apart in memory wreck the cache. Sorting along a space-filling curve
// at load puts spatial neighbours next to each other.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::neighbourhood {

/// A permutation (new i = old order[i]) sorting the points along a Morton (Z-order) curve over their bounding box.
std::vector<std::uint32_t> spatial_order(const std::vector<Vec3f>& points);

/// Reorders the cloud spatially in place; `cloud.source_index` keeps the mapping back to file order.
void reorder_spatially(PointCloud& cloud);

}  // namespace pcsketch::neighbourhood
