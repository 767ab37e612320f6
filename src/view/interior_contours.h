#pragma once
// Interior contours: the rim samples the outline does not already draw, chained in 3D.

#include <vector>

#include "core/progress.h"
#include "pcsketch/view/contours.h"

namespace pcsketch::view::detail {

/// Chains the interior rim samples of `cp` in 3D with the paper's rule (nearest ahead within z_max of the direction
/// line), after dropping those `outline` already covers. `h`: the cloud's mean spacing. On a `denoised` cloud the
/// chains are held to denoised_min_length_factor, and to denoised_min_bending where ContourPoints::rim_bends was
/// filled (ContourOptions). Reports to `steps` after the outline's seeds.
std::vector<Polyline> trace_interior(const ContourPoints& cp, const std::vector<Polyline>& outline, float h,
                                     const ContourOptions& o, bool denoised, pcsketch::detail::ProgressSteps& steps);

}  // namespace pcsketch::view::detail
