#pragma once
// Thin parts: a plate about as thick as a neighbourhood is wide puts points of both its faces in one list.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential::detail {

/// A gap along the normal this fraction of the list's radius (its farthest neighbour) wide can split it.
inline constexpr double kFaceGap = 0.15;

/// A point's neighbours on its own side of a gap along its normal (own_face).
struct FaceSplit {
  std::size_t kept = 0;  ///< neighbours on the point's side; the list's size where nothing splits it
  double low = 0;        ///< the band of offsets n·(p − p_i) on its side: halfway to the next face below
  double high = 0;       ///< and above (±infinity where no face lies on that side)
};

/// The run of offsets n·(p_j − p_i) of the list `nb[0..k)` around the point's own 0 in which no step exceeds `gap`,
/// where the steps that bound it exceed three times its spread and twice the spread beyond them: noise leaves random
/// gaps between one face's offsets, and a crease's other face rises with the distance from the edge, where a
/// parallel face stands off by far more than either spreads (docs/geometry.md, "Thin parts"). Marks the run's
/// neighbours in `own`.
FaceSplit own_face(const std::vector<Vec3f>& points, std::size_t i, const std::uint32_t* nb, std::size_t k,
                   const Vec3d& normal, double gap, std::array<bool, neighbourhood::kMaxNeighbours>& own);

/// Rewrites the lists of the points `split` (those whose normal own_face_normal took) to their k nearest on their
/// own face: the other face's points are replaced by the nearest of their own-face neighbours' neighbours that lie
/// on the point's side, so that every later stage (noise, denoising, curvature, contours) sees one face.
/// Returns how many lists changed.
std::size_t separate_faces(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                           const std::vector<std::uint32_t>& split, neighbourhood::Neighbourhoods& neighbourhoods);

}  // namespace pcsketch::differential::detail
