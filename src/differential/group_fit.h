#pragma once
// Wide curvature fits shared by small groups of nearby points: the fit size a noisy cloud needs, at a fraction of
// the cost of one fit per point.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/differential/curvature.h"
#include "pcsketch/neighbourhood/kd_tree.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential::detail {

/// Defaults measured on the noisy-sphere and cube tests and bench_scans (docs/geometry.md, "Group fits").
struct GroupFitOptions {
  std::size_t fit = 0;          ///< points per fit (the support's radius is estimated to hold this many)
  double reach = 0.3;           ///< group cells are 2·reach fit radii wide
  double noise_sigma = 0;       ///< the cloud's noise σ̂, model units
  double misfit_factor = 5;     ///< cubic residual variance over this × σ̂²: fit each point on its own
  double cubic_shrink = 4;      ///< the cubic terms count in full only where they remove ≫ this × σ̂²
  bool shared_at_creases = false;  ///< a crease's points are fitted over their shared k, not their own ball
  ProgressFn progress;
  std::string_view stage = "curvature";  ///< the progress stage name
};

/// Fits point i over the given neighbours (i excluded) and stores its curvature.
using PointFitFn = std::function<void(std::size_t i, const std::uint32_t* neighbours, std::size_t count)>;

/// Points grouped by the cells of a grid of side 2·`fraction` × the median estimated fit radius (a point's shared
/// k-th distance scaled to `fit` neighbours), at most `max_size` points a group.
struct Groups {
  std::vector<std::uint32_t> members;  ///< point indices, group by group
  std::vector<std::size_t> starts;     ///< group g is members[starts[g], starts[g + 1])
  std::size_t size() const { return starts.size() - 1; }
  std::span<const std::uint32_t> of(std::size_t g) const {
    return {members.data() + starts[g], starts[g + 1] - starts[g]};
  }
};
Groups make_groups(const std::vector<Vec3f>& points, const neighbourhood::Neighbourhoods& shared, std::size_t fit,
                   double fraction, std::size_t max_size);

/// One height field z = h(x, y) per group (make_groups), fitted by unweighted least squares to the points within
/// the radius estimated to hold `fit` of them around the group's centroid, in the tangent frame of its mean normal:
/// the quadric plus shrunk cubic terms (GroupFitter::solve). Each point of the group takes the principal curvatures
/// of that graph at its own (x, y), its directions projected onto its own normal's tangent plane. Where the cubic
/// leaves more than the noise (a crease in the support), each point is fitted on its own ball by `point_fit`, or
/// over its shared neighbours with `shared_at_creases`.
/// Writes k1, k2, dir1, dir2 of every point; returns how many points were fitted one by one.
std::size_t fit_groups(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals,
                       const neighbourhood::Neighbourhoods& shared, const neighbourhood::KdTree& tree,
                       const GroupFitOptions& options, const PointFitFn& point_fit, Curvature& result);

}  // namespace pcsketch::differential::detail
