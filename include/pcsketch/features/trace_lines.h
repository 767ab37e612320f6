#pragma once
// Connecting ridge/valley points into polylines: the paper's PCA-guided growth (§IV.A, second step).

#include <cstdint>
#include <optional>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/features/ridge_valley_points.h"

namespace pcsketch::features {

struct TraceOptions {
  /// Paper's neighbourhood radius r, in units of h: the feature points within r of the current centre decide the
  /// direction (PCA) and the next centre. Paper Fig. 4 uses r = 0.1…0.3 model units; a multiple of h works at any
  /// scale. After non-maximum suppression a sharp edge keeps about one feature point per h or two of its length, so
  /// 6h holds enough of them for a stable PCA and bridges the gaps noise leaves, while staying below the size of
  /// small features.
  float radius_factor = 6.f;
  /// Absolute r in model units; overrides radius_factor when set.
  std::optional<float> radius;
  /// Half-width of the corridor around the current direction, as a fraction of r: only feature points closer than
  /// this to the line through the centre along the direction take part in a step. 0.5 follows curves of radius ≥ r
  /// and stops at corners, where the other edges leave the corridor, instead of cutting across them.
  float corridor_fraction = 0.5f;
  /// Largest change of direction (degrees) between two steps; a sharper turn ends the line. The lines meeting at a
  /// corner are traced separately (and not joined: see JoinOptions::join_angle_beta_deg). 30° per step of about
  /// 0.75 r follows curves of radius down to about 1.4 r.
  float max_turn_deg = 30.f;
};

/// Ordered lines of one cloud; lines are in the order of their seed point (ridges and valleys interleaved).
struct TraceResult {
  std::vector<Polyline> lines;       ///< kind Ridge or Valley; per-vertex curvature and point_index filled
  std::vector<std::uint32_t> seeds;  ///< one per line: index of the point the line was grown from
  float radius = 0;                  ///< r actually used, model units
};

/// Grows polylines through the labelled points, ridges and valleys separately (a line never mixes them). Seeds are
/// taken in increasing point index. From a seed, the feature points within r give a start centre (their mean) and a
/// direction (their principal axis, PCA); each step takes the feature points within r ahead of the centre inside the
/// corridor, moves the centre to the mean of the farther half of them (so the line runs along the middle of the band
/// of feature points instead of zig-zagging through it) and re-estimates the direction by PCA there; growth runs both
/// ways until no point lies ahead. Points within the corridor of a finished line are used up and cannot seed or
/// extend another line. A line that comes back to its start is closed. Sequential and deterministic.
/// Vertex data: `curvature` = mean feature curvature k_i of the points of the step, `point_index` = the point nearest
/// to the vertex.
/// @param[in] points #P positions
/// @param[in] labels #P labels (detect_ridge_valley_points)
/// @param[in] feature_curvature #P signed k_i (detect_ridge_valley_points)
/// @param[in] spacing mean spacing h, model units
/// @param[in] progress optional, reports "ridge/valley tracing" (not an option field: TraceOptions is built with
///            designated initializers inside other options, where GCC 12 misreports a std::function member)
/// @throws pcsketch::Error if the sizes differ, r would not be positive, or an option is out of range.
TraceResult trace_lines(const std::vector<Vec3f>& points, const std::vector<PointLabel>& labels,
                        const std::vector<float>& feature_curvature, float spacing, const TraceOptions& options = {},
                        const ProgressFn& progress = {});

}  // namespace pcsketch::features
