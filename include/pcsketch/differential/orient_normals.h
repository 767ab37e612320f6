#pragma once
// One consistent normal orientation over the whole cloud.

#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

struct OrientOptions {
  ProgressFn progress;  ///< optional
};

struct OrientResult {
  std::size_t components = 0;  ///< connected components of the neighbour graph, each oriented on its own
  std::size_t flipped = 0;     ///< normals whose sign was changed
  Warnings warnings;
};

/// Flips normals in place so that neighbours agree (propagation along a maximum-|n_i·n_j| spanning tree of the
/// neighbour graph, Hoppe et al. 1992), then turns each component outward: the point farthest from the component's
/// centroid must have its normal pointing away from the centroid.
OrientResult orient_normals(const std::vector<Vec3f>& points, std::vector<Vec3f>& normals,
                            const neighbourhood::Neighbourhoods& neighbourhoods, const OrientOptions& options = {});

}  // namespace pcsketch::differential
