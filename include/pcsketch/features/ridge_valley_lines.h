#pragma once
// Ridge and valley lines of a cloud in one call: detection, tracing, joining (paper §IV.A).

#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/core/report.h"
#include "pcsketch/differential/surface.h"
#include "pcsketch/features/join_lines.h"
#include "pcsketch/features/ridge_valley_points.h"
#include "pcsketch/features/trace_lines.h"

namespace pcsketch::features {

struct RidgeValleyOptions {
  DetectionOptions detection;  ///< step 1: which points are ridge/valley points
  TraceOptions tracing;        ///< step 2: connecting them into polylines
  JoinOptions joining;         ///< step 3: joining broken lines, dropping short ones, smoothing
  ProgressFn progress;         ///< optional, reported by every step
};

/// Seconds per step (paper Table 2: "ridge-valley points extraction" = detection, "connection" = tracing + joining).
struct RidgeValleyTimings {
  double detection = 0, tracing = 0, joining = 0;
};

struct RidgeValleyLines {
  std::vector<Polyline> lines;  ///< ridge and valley lines, view-independent, cloud's relative coordinates
  DetectionResult detection;    ///< per-point labels (#P) and k_i, thresholds used
  float radius = 0;             ///< tracing radius r, model units
  std::size_t joins = 0;        ///< joins made by the optimisation step
  std::size_t dropped = 0;      ///< lines dropped as too short
  RidgeValleyTimings timings;
  Warnings warnings;            ///< no feature point found, or none of them made a line long enough
};

/// Runs detect_ridge_valley_points, trace_lines and join_lines on a cloud analysed by differential::analyse_surface
/// (same point order: analyse_surface reorders the cloud in place).
/// @throws pcsketch::Error if `surface` does not belong to `cloud` (sizes differ) or an option is out of range.
RidgeValleyLines extract_ridge_valley_lines(const PointCloud& cloud, const differential::Surface& surface,
                                            const RidgeValleyOptions& options = {});

}  // namespace pcsketch::features
