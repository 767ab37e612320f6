#pragma once
// Joining broken ridge/valley lines and dropping short ones: the paper's optimisation step (§IV.A, Fig. 5).

#include <cstddef>
#include <optional>
#include <vector>

#include "pcsketch/core/polyline.h"

namespace pcsketch::features {

struct JoinOptions {
  /// Paper's distance threshold α·r: endpoints p, q of two lines can join when |p − q| ≤ join_distance_alpha · r
  /// (r = the tracing radius). The paper reuses the detection α here; this is its own factor. 1.5 bridges a gap of
  /// 1.5 r (9h at the default r = 6h): the breaks noise leaves in an edge, not the space between two features.
  float join_distance_alpha = 1.5f;
  /// Paper's angle β, degrees: the end tangents (taken over 2r of each line) must be opposite within β. For a gap
  /// longer than r each tangent must also aim at the other endpoint within β; for a shorter gap, where the lateral
  /// offset of the ends (about h) would swamp that angle, each end must merely lie ahead of the other. 30° joins
  /// lines broken along a gently curving feature and never joins lines meeting at a corner (90° on a cube).
  float join_angle_beta_deg = 30.f;
  /// Lines shorter than this many h (after joining) are dropped as noise. 8h, under two tracing steps at the
  /// default r: shorter lines are a blob of a few feature points, not a feature.
  float min_length_factor = 8.f;
  /// Absolute minimum length in model units; overrides min_length_factor when set.
  std::optional<float> min_length;
  /// Laplacian smoothing passes applied to each kept line; endpoints of open lines do not move. 2 removes the
  /// residual wobble of the band centres without shortening lines or rounding corners noticeably. 0 = off.
  int smoothing_iterations = 2;
  /// Weight of one smoothing pass: a vertex moves this fraction of the way to the mean of its two neighbours.
  float smoothing_weight = 0.5f;
};

struct JoinResult {
  std::vector<Polyline> lines;  ///< in the order of their first input line
  std::size_t joins = 0;        ///< endpoint pairs joined (a line closed on itself counts once)
  std::size_t dropped = 0;      ///< lines removed as shorter than the minimum length
};

/// Joins lines of the same kind end to end while two endpoints qualify (see JoinOptions; best pair = closest first,
/// ties by line order), repeats until nothing joins, drops short lines, smooths. A line whose two ends qualify is
/// closed. Deterministic: depends only on the order of `lines` (trace_lines gives them by seed index).
/// Per-vertex curvature and point_index arrays, when present, follow their vertices.
/// @param[in] lines traced lines (kind Ridge/Valley; other kinds are joined among themselves in the same way)
/// @param[in] radius the tracing radius r, model units
/// @param[in] spacing mean spacing h, model units
/// @throws pcsketch::Error if radius or spacing is not positive or an option is out of range.
JoinResult join_lines(std::vector<Polyline> lines, float radius, float spacing, const JoinOptions& options = {});

}  // namespace pcsketch::features
