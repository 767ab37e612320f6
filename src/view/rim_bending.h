#pragma once
// Whether the surface bends across an interior rim sample. Noise flips the sign of n·v on a face seen nearly edge-on
// too, but there n·v is flat around the sample, while at a true rim it changes with position.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::view::detail {

/// For each point i of `points`: whether `facing` (n·v per point) over i, its m nearest neighbours and theirs varies
/// with position across i's tangent plane beyond its scatter. That is the F statistic of a least-squares plane
/// f = a + g·(x, y) against a constant f, with 2 and (count − 3) degrees of freedom, reaching `min_f`. Fewer than 8
/// distinct points: true (too few to tell).
std::vector<char> rim_bends(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods, const std::vector<float>& facing,
                            const std::vector<std::uint32_t>& points, std::size_t m, float min_f);

}  // namespace pcsketch::view::detail
