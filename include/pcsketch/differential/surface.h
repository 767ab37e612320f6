#pragma once
// The view-independent analysis of a cloud, run once and shared by every view: reorder, neighbourhoods, spacing,
// normals, orientation, curvature.

#include <optional>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/differential/curvature.h"
#include "pcsketch/differential/normals.h"
#include "pcsketch/differential/orient_normals.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

struct SurfaceOptions {
  neighbourhood::NeighbourhoodOptions neighbourhood;
  NormalOptions normals;
  CurvatureOptions curvature;
  bool recompute_normals = false;  ///< ignore normals read from the file (they are kept by default)
  bool reorder = true;             ///< sort points along a space-filling curve first (faster; source_index maps back)
  ProgressFn progress;             ///< optional, passed to every step
};

/// Seconds spent in each step, for --timings and bench/.
struct SurfaceTimings {
  double reorder = 0, kd_tree = 0, neighbourhoods = 0, normals = 0, orientation = 0, curvature = 0;
};

struct Surface {
  neighbourhood::Neighbourhoods neighbourhoods;
  float spacing = 0;  ///< mean point spacing h, model units
  Curvature curvature;
  SurfaceTimings timings;
  Warnings warnings;
};

/// Runs every view-independent step on `cloud`, which it reorders and gives normals (oriented) in place.
/// Throws pcsketch::Error for a cloud with fewer than 3 distinct points.
Surface analyse_surface(PointCloud& cloud, const SurfaceOptions& options = {});

}  // namespace pcsketch::differential
