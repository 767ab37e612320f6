#pragma once
// Occluding contours where a surface ends in front of another: a scan recorded from one side has no points past its
// interior contours, so n·v never changes sign there, and the surface behind fills the image beyond them.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/view/camera.h"
#include "pcsketch/view/contours.h"

namespace pcsketch::view::detail {

/// Appends a rim sample to cp.rim for every depth-edge point (see ContourOptions::depth_edge_factor): marked in
/// `border` (the surface ends there), not facing the viewer, its projected neighbours leave a gap over
/// gap_threshold_deg, and the points in the image within depth_edge_radius_factor spacings and
/// ±confirm_half_angle_deg of that gap's bisector exist and all lie more than depth_edge_factor · h behind it. The
/// sample is the point moved along its ray to the mean depth of the edge points among its interior_neighbours.
/// Nothing without a border or with depth_edge_factor 0. Reads cp.projected and cp.spacing_px.
void add_depth_edge_samples(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods,
                            const std::vector<std::uint8_t>& border, float h, const Camera& camera,
                            const ContourOptions& o, ContourPoints& cp);

}  // namespace pcsketch::view::detail
