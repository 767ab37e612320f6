#include "pcsketch/features/boundary_lines.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "core/angles.h"
#include "core/angular_gap.h"
#include "core/parallel_chunks.h"
#include "core/tangent_frame.h"
#include "core/union_find.h"
#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/kd_tree.h"

namespace pcsketch::features {

namespace {

using pcsketch::detail::kDegToRad;
constexpr std::uint8_t kBorder = 1, kHole = 2;
constexpr std::uint32_t kMinRimPoints = 8;

/// The gap's bisector in 3D when point i is a border candidate: its neighbours, projected onto its tangent plane,
/// leave a gap over the threshold, none of them reaches far towards it, and none lies across a fold.
std::optional<Vec3f> candidate_gap(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                   const neighbourhood::Neighbourhoods& nbh, std::size_t i, const BoundaryOptions& o,
                                   std::vector<Vec2f>& dirs, std::vector<float>& angles) {
  const Vec3f& n = normals[i];
  if (!(n.squaredNorm() > 0.5f)) return std::nullopt;
  Vec3f u, v;
  pcsketch::detail::tangent_frame(n, u, v);
  // Every direction is written and the usable ones counted: no branch on the test, which is rarely false.
  dirs.resize(nbh.k);
  std::size_t count = 0;
  std::uint16_t sectors = 0;
  for (const std::uint32_t j : nbh.of(i)) {
    const Vec3f d = positions[j] - positions[i];
    const Vec2f c(d.dot(u), d.dot(v));
    const bool usable = c.squaredNorm() > 1e-12f * d.squaredNorm() && c.squaredNorm() > 0;
    dirs[count] = c;
    count += usable;
    sectors |= static_cast<std::uint16_t>(usable ? pcsketch::detail::sector_bit(c) : 0);
  }
  dirs.resize(count);
  // Neighbours all round leave no run of empty 22.5° sectors as wide as the gap: most points settle here unsorted.
  const float threshold = o.gap_threshold_deg * kDegToRad;
  if (pcsketch::detail::sectors_rule_out_gap(sectors, threshold)) return std::nullopt;
  if (!pcsketch::detail::gap_exceeds(dirs, threshold)) return std::nullopt;
  const Vec2f b = pcsketch::detail::largest_gap(angles, dirs).second;
  const float reach = nbh.distances[i * nbh.k + nbh.k - 1];
  for (const Vec2f& c : dirs)
    if (c.dot(b) > o.edge_band_fraction * reach) return std::nullopt;
  const float cos_fold = std::cos(o.fold_deg * kDegToRad);
  for (const std::uint32_t j : nbh.of(i))
    if (std::abs(normals[j].dot(n)) < cos_fold) return std::nullopt;
  return Vec3f(b.x() * u + b.y() * v);
}

/// std::sqrt(squared) <= limit, decided as it would be, with the root taken only within 1e-5 of the limit (where the
/// rounding of the squares could matter; it is 1e-7).
bool root_at_most(float squared, float limit) {
  const float limit2 = limit * limit;
  if (limit2 >= std::numeric_limits<float>::min()) {
    if (squared < limit2 * (1 - 1e-5f)) return true;
    if (squared > limit2 * (1 + 1e-5f)) return false;
  }
  return std::sqrt(squared) <= limit;
}

/// What lies in the cone around a candidate's gap (see BoundaryOptions::confirm_factor): the distance of the nearest
/// point there beyond the candidate's shared neighbours, within 45° of its tangent plane.
class Cone {
 public:
  Cone(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals, const neighbourhood::Neighbourhoods& nbh,
       const BoundaryOptions& o)
      : positions_(positions), normals_(normals), nbh_(nbh), factor_(o.confirm_factor),
        cos_cone_(std::cos(o.confirm_half_angle_deg * kDegToRad)) {}

  /// The neighbours of i's neighbours reach about 2r: one of them in the cone settles the sampling's own gaps and
  /// the changes of density without a radius query.
  bool filled_nearby(std::size_t i, const Vec3f& bisector) const {
    const float hole = kHoleFactor * reach(i);
    for (const std::uint32_t j : nbh_.of(i))
      for (const std::uint32_t q : nbh_.of(j))
        if (distance_inside(i, bisector, q) <= hole) return true;
    return false;
  }

  /// Nearest distance from i of a point in its cone, out to confirm_factor · r; infinity if there is none. The
  /// smallest needs no order: the points come unsorted.
  float nearest(std::size_t i, const Vec3f& bisector, const neighbourhood::KdTree& tree,
                std::vector<std::uint32_t>& found) const {
    tree.radius_any_order(positions_[i], factor_ * reach(i), found);
    float best = kNone;
    for (const std::uint32_t q : found) best = std::min(best, distance_inside(i, bisector, q));
    return best;
  }

  float reach(std::size_t i) const { return nbh_.distances[i * nbh_.k + nbh_.k - 1]; }

  /// Beyond this many r, an empty cone is a hole: where the density changes 4:1, about 6 points of the sparse side
  /// lie in the cone within it.
  static constexpr float kHoleFactor = 2.5f;
  static constexpr float kNone = std::numeric_limits<float>::infinity();

 private:
  /// q's distance from i if q lies in i's cone beyond r, else kNone. The tests that most often fail come first, on
  /// squared lengths: most of the points asked lie within r, or behind i.
  float distance_inside(std::size_t i, const Vec3f& bisector, std::uint32_t q) const {
    const Vec3f d = positions_[q] - positions_[i];
    const float squared = d.squaredNorm(), r = reach(i);
    if (root_at_most(squared, r) || !root_at_most(squared, factor_ * r)) return kNone;
    const Vec3f& n = normals_[i];
    const Vec3f in_plane = d - d.dot(n) * n;
    const float along = in_plane.dot(bisector);
    if (cos_cone_ >= 0 && along <= 0) return kNone;  // then along > cos_cone_ · length fails
    const float length = in_plane.norm();
    return std::abs(d.dot(n)) <= length && along > cos_cone_ * length ? std::sqrt(squared) : kNone;
  }

  const std::vector<Vec3f>& positions_;
  const std::vector<Vec3f>& normals_;
  const neighbourhood::Neighbourhoods& nbh_;
  float factor_, cos_cone_;
};

/// kBorder where the cone is empty out to confirm_factor · r, kHole where it is empty out to 2.5r (a hole smaller than
/// the cone), Boundary::kEdge where it is filled farther out (the surface ends in front of another), 0 elsewhere.
/// Candidates in parallel, then the neighbours' neighbours, then a radius query for the candidates they leave (where
/// the density changes, the two rings may stay on the dense side).
std::vector<std::uint8_t> border_points(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                        const neighbourhood::Neighbourhoods& nbh, const BoundaryOptions& o,
                                        const neighbourhood::KdTree* given_tree) {
  const std::size_t n = positions.size();
  const Cone cone(positions, normals, nbh, o);
  // The candidates the two rings leave open and their gaps' bisectors, in any order: each is settled on its own.
  std::vector<std::pair<std::uint32_t, Vec3f>> left;
  std::mutex adding;
  // The candidates are most of the stage's time: their loop reports its progress.
  pcsketch::detail::parallel_chunks(n, o.progress, "boundaries", [&](std::size_t begin, std::size_t end) {
    std::vector<Vec2f> dirs;
    std::vector<float> angles;
    std::vector<std::pair<std::uint32_t, Vec3f>> open;
    for (std::size_t i = begin; i != end; ++i)
      if (const auto b = candidate_gap(positions, normals, nbh, i, o, dirs, angles); b && !cone.filled_nearby(i, *b))
        open.emplace_back(static_cast<std::uint32_t>(i), *b);
    if (open.empty()) return;
    const std::lock_guard lock(adding);
    left.insert(left.end(), open.begin(), open.end());
  });
  std::vector<std::uint8_t> rim(n, 0);
  if (left.empty()) return rim;
  std::optional<neighbourhood::KdTree> own_tree;
  const neighbourhood::KdTree& tree = given_tree ? *given_tree : own_tree.emplace(positions);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, left.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::uint32_t> found;
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      const auto& [i, bisector] = left[c];
      const float nearest = cone.nearest(i, bisector, tree, found);
      rim[i] = nearest == Cone::kNone ? kBorder : nearest > Cone::kHoleFactor * cone.reach(i) ? kHole : Boundary::kEdge;
    }
  });
  return rim;
}

/// One connected set of rim points.
struct RimSet {
  Eigen::AlignedBox3f box;
  std::uint32_t points = 0;
  bool bordered = false;  ///< holds a border point, not only a hole's rim
};

/// The points of `rim` (border or hole rims) in connected sets that hold a border point and span at least
/// `min_size` (largest side of their bounding box), ascending; `small` counts the other sets. Sets of fewer than
/// kMinRimPoints are marked Boundary::kEdge, the others Boundary::kDrawnRim or kUndrawnRim: the rim of a hole a cone
/// wide holds dozens. The points already kEdge are no rim and stay so. Past the scan for them, only the rim points are
/// visited (a closed cloud has few or none), numbered by their places among them.
std::vector<std::uint32_t> drawn_sets(const std::vector<Vec3f>& positions, const neighbourhood::Neighbourhoods& nbh,
                                      std::vector<std::uint8_t>& rim, float min_size, std::size_t& small) {
  const auto is_rim = [&](std::uint32_t i) { return rim[i] == kBorder || rim[i] == kHole; };
  std::vector<std::uint32_t> points;
  for (std::uint32_t i = 0; i < rim.size(); ++i)
    if (is_rim(i)) points.push_back(i);
  const auto place = std::make_unique_for_overwrite<std::uint32_t[]>(rim.size());  // read at rim points only
  for (std::uint32_t p = 0; p < points.size(); ++p) place[points[p]] = p;
  // Places ascend with the indices: a set's root is still its smallest point, and comes first in it.
  pcsketch::detail::Clusters sets(points.size());
  for (std::uint32_t p = 0; p < points.size(); ++p)
    for (const std::uint32_t j : nbh.of(points[p]))
      if (is_rim(j)) sets.join(p, place[j]);
  std::vector<RimSet> records;
  std::vector<std::uint32_t> set_of(points.size());
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    const std::uint32_t root = sets.find(p);
    if (root == p) records.emplace_back();
    set_of[p] = root == p ? static_cast<std::uint32_t>(records.size() - 1) : set_of[root];
    RimSet& set = records[set_of[p]];
    set.box.extend(positions[points[p]]);
    ++set.points;
    set.bordered |= rim[points[p]] == kBorder;
  }
  const auto kept = [&](const RimSet& set) { return set.bordered && set.box.sizes().maxCoeff() >= min_size; };
  small = static_cast<std::size_t>(std::count_if(
      records.begin(), records.end(), [&](const RimSet& set) { return set.points >= kMinRimPoints && !kept(set); }));
  std::vector<std::uint32_t> drawn;
  for (std::uint32_t p = 0; p < points.size(); ++p) {
    const RimSet& set = records[set_of[p]];
    // Fewer points: a stray mark (a random gap of the sampling, a change of density), not the rim of anything; or a
    // piece of an edge whose cone fills and empties along it (an edge in front of another surface, about 3r behind).
    rim[points[p]] = set.points < kMinRimPoints ? Boundary::kEdge
                     : kept(set)                ? Boundary::kDrawnRim
                                                : Boundary::kUndrawnRim;
    if (rim[points[p]] == Boundary::kDrawnRim) drawn.push_back(points[p]);
  }
  return drawn;
}

}  // namespace

Boundary find_boundaries(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                         const neighbourhood::Neighbourhoods& neighbourhoods, float spacing,
                         const BoundaryOptions& options, const neighbourhood::KdTree* tree) {
  const std::size_t n = positions.size();
  if (tree && tree->size() != n) throw Error("boundary: the kd-tree does not index these points");
  if (normals.size() != n || neighbourhoods.size() != n)
    throw Error("boundary: " + std::to_string(normals.size()) + " normals and " +
                std::to_string(neighbourhoods.size()) + " neighbourhoods for " + std::to_string(n) + " points");
  if (!(spacing > 0) || !std::isfinite(spacing)) throw Error("boundary: the mean spacing h must be positive");
  if (!(options.gap_threshold_deg > 0 && options.gap_threshold_deg < 360) ||
      !(options.confirm_half_angle_deg > 0 && options.confirm_half_angle_deg < 90) ||
      !(options.fold_deg > 0 && options.fold_deg <= 90) || !(options.confirm_factor >= 1) ||
      !(options.min_size_factor >= 0) || !(options.edge_band_fraction > 0 && options.edge_band_fraction <= 1) ||
      !std::isfinite(options.confirm_factor + options.min_size_factor))
    throw Error("boundary: an option is out of range (gap in (0, 360), cone in (0, 90), fold in (0, 90] degrees, "
                "confirm factor ≥ 1, edge band in (0, 1], minimum size ≥ 0)");
  Boundary result;
  if (!options.enabled || n == 0 || neighbourhoods.k == 0) return result;
  result.border = border_points(positions, normals, neighbourhoods, options, tree);

  const std::vector<std::uint32_t> drawn =
      drawn_sets(positions, neighbourhoods, result.border, options.min_size_factor * spacing, result.small_holes);
  result.border_points = drawn.size();
  if (drawn.empty()) return result;
  std::vector<PointLabel> labels(n, PointLabel::None);
  for (const std::uint32_t i : drawn) labels[i] = PointLabel::Ridge;
  TraceResult traced = trace_lines(positions, labels, std::vector<float>(n, 0.f), spacing, options.tracing);
  JoinResult joined = join_lines(std::move(traced.lines), traced.radius, spacing, options.joining);
  for (Polyline& line : joined.lines) {
    line.kind = LineKind::Boundary;
    line.curvature.clear();
  }
  result.lines = std::move(joined.lines);
  return result;
}

}  // namespace pcsketch::features
