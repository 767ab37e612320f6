#pragma once
// The view-independent analysis of a cloud, run once and shared by every view: reorder, neighbourhoods, spacing,
// normals, orientation, curvature.

#include <optional>

#include "pcsketch/clean/outliers.h"
#include "pcsketch/clean/scan_lines.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/differential/curvature.h"
#include "pcsketch/differential/denoise.h"
#include "pcsketch/differential/normals.h"
#include "pcsketch/differential/orient_normals.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential {

struct SurfaceOptions {
  neighbourhood::NeighbourhoodOptions neighbourhood;
  clean::OutlierOptions outliers;
  clean::ScanLineOptions scan_lines;
  DenoiseOptions denoise;
  NormalOptions normals;
  OrientOptions orientation;
  CurvatureOptions curvature;
  /// Ignore normals read from the file and estimate them by PCA. By default file normals are trusted as they are
  /// (scanners and meshers know the true orientation better than propagation); invalid ones (zero, NaN) force a
  /// recompute with a warning.
  bool recompute_normals = false;
  /// Run the orientation pass over file normals too (for files whose normals have arbitrary signs).
  bool orient_file_normals = false;
  /// File normals are also re-oriented, with a warning, when more than this fraction of neighbour pairs surely
  /// disagree in sign (sign_disagreement): their directions are kept, their signs are not trusted. Consistent file
  /// normals give about 0 (hippo1.ply 0.0000); building.ply's give 0.098, and drawn as they were its façades filled
  /// with interior contours where the sign flipped. 1 never re-orients on its own.
  double file_normal_disagreement = 0.01;
  bool reorder = true;             ///< sort points along a space-filling curve first (faster; source_index maps back)
  ProgressFn progress;             ///< optional, passed to every step whose own progress is empty
};

/// Seconds spent in each step, for --timings and bench/. `neighbourhoods` includes the kd-tree's build, which runs
/// beside the neighbour search.
struct SurfaceTimings {
  double reorder = 0, neighbourhoods = 0, scan_lines = 0, outliers = 0, denoise = 0, normals = 0, orientation = 0,
         curvature = 0;
};

struct Surface {
  neighbourhood::Neighbourhoods neighbourhoods;
  float spacing = 0;  ///< mean point spacing h, model units
  /// The points left out as outliers (clean::find_outliers), with their source_index: the cloud no longer holds
  /// them, the user's data still does.
  PointCloud outliers;
  std::size_t isolated_outliers = 0, clustered_outliers = 0;  ///< how many of them were isolated / in small clumps
  clean::ScanLines scan_lines;  ///< whether the points lie on scan lines, and the lines' spacing
  /// On scan lines, the points the thinning to the lines' spacing left out, with their source_index.
  PointCloud thinned;
  Curvature curvature;
  bool normals_estimated = false;  ///< normals come from PCA (not from the file)
  bool denoised = false;           ///< the points were moved by denoise() (the noise exceeded its trigger)
  float input_noise = 0;           ///< σ̂ of the cloud as read, model units (0 when denoising is off)
  /// Angular noise of the final normals, radians: differential::normal_noise, capped by the tilt σ̂ can explain
  /// (0.25 rad per σ̂/h) when σ̂ was estimated, so that a sparse cloud's bending is not taken for noise.
  float normal_noise = 0;
  std::size_t components = 0;      ///< connected components found by the orientation (0 if it did not run)
  /// Points on a thin part whose lists reached its other face, their normal and list taken on their own face
  /// (docs/geometry.md, "Thin parts").
  std::size_t own_face_lists = 0;
  SurfaceTimings timings;
  Warnings warnings;
};

/// Runs every view-independent step on `cloud`, which it reorders, thins when it lies on scan lines (the points left
/// out moved to Surface::thinned), rids of outliers (moved to Surface::outliers), denoises when noisy and gives
/// normals (oriented) in place.
/// Collinear or coplanar clouds get a defined result (arbitrary perpendicular normals, zero curvature) and warnings.
/// @param tree_out when given, receives the kd-tree over `cloud.positions` as left (the analysis builds one), so that
///        later stages need not build it again; left empty when the points were denoised (the tree then indexes the
///        raw points). It refers to `cloud.positions`, which must stay where it is while the tree is used.
/// @throws pcsketch::Error for a cloud with fewer than 3 distinct points (nothing to call a surface)
Surface analyse_surface(PointCloud& cloud, const SurfaceOptions& options = {},
                        std::optional<neighbourhood::KdTree>* tree_out = nullptr);

}  // namespace pcsketch::differential
