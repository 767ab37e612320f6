#pragma once
// One point per small cell of the image: where a view looks along a face (a CAD part seen from the front), the whole
// face projects onto one curve, hundreds of points per pixel of it, and every image-plane query there scans them all.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::view::detail {

/// The members of `valid` (indices into `projected`, increasing) that come first, by index, in their cell of a grid of
/// `cell` pixels in the image; increasing. Deterministic for any thread count.
std::vector<std::uint32_t> first_in_image_cells(const std::vector<Vec3f>& projected, std::vector<std::uint32_t> valid,
                                                float cell);

/// The 5th percentile of spacing_px over `valid` (0 if empty): the spacing of the cloud's densest parts, pixels.
float low_spacing(const std::vector<float>& spacing_px, const std::vector<std::uint32_t>& valid);

}  // namespace pcsketch::view::detail
