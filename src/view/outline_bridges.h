#pragma once
// Closing the outline's gaps on sparse and uneven clouds. The gap test finds only the points whose neighbours leave a
// wide empty angle; along a ragged rim of a few thousand points those lie further apart than the walk's radius, and
// the traced outline breaks into pieces. From each open end, a disc rolls along the outermost points of the whole
// projected cloud (2D ball pivoting: the edge of the union of discs around the points) until it meets the outline.

#include <vector>

#include "pcsketch/core/polyline.h"
#include "pcsketch/view/contours.h"

namespace pcsketch::view::detail {

/// Bridges the open ends of `outline` (traced from `cp`, vertices cloud points) to the rest of the outline, and joins
/// each bridge with the lines that end where it does (a piece, its bridge and the next piece become one line). A disc
/// of radius bridge_radius_factor × the point's h_px pivots from the end, the empty side kept; a bridge ends at a
/// vertex of another outline line, of an earlier bridge, or of its own line away from the end. It is kept only when it
/// is no longer than the longer line it joins (a longer roll went round a hole, or along the cloud's far side) and
/// within max_bridge_steps. Deterministic; nothing changes when the factor is 0 or every line is closed.
void bridge_outline(const ContourPoints& cp, const std::vector<Vec3f>& positions, std::vector<Polyline>& outline,
                    const ContourOptions& o);

}  // namespace pcsketch::view::detail
