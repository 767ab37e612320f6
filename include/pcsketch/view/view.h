#pragma once
// One view of an analysed cloud: contours (paper §IV.B) and the visibility of every line. Everything
// view-independent (the Surface, the lines, the SurfaceScene) is computed once and passed in, so a second view
// costs only projection, contour extraction and ray casting.

#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/core/report.h"
#include "pcsketch/differential/surface.h"
#include "pcsketch/view/camera.h"
#include "pcsketch/view/contours.h"
#include "pcsketch/view/surface_scene.h"
#include "pcsketch/view/visibility.h"

namespace pcsketch::view {

struct ViewOptions {
  ContourOptions contours;
  VisibilityOptions visibility;
  ProgressFn progress;  ///< optional, passed to the steps whose own progress is empty
};

/// Seconds per step, named after the paper's Table 2 rows.
struct ViewTimings {
  double contour_points = 0;      ///< "contour points extraction": projection, boundary points, rim samples
  double contour_connection = 0;  ///< "contour connection": tracing into polylines
  double visibility = 0;          ///< ray casting of every line (contours, ridges, valleys)
};

struct ViewResult {
  Camera camera;
  ContourPoints contour_points;  ///< projection of every point and the contour points (for stylization, debugging)
  /// The view's outline contours, then its interior contours (kind Contour), then the input lines in their order,
  /// each with visibility.
  std::vector<ViewLine> lines;
  std::size_t contour_count = 0;  ///< how many of `lines` are this view's contours
  std::size_t outline_count = 0;  ///< how many of them (the first) are the outline
  ViewTimings timings;
  Warnings warnings;
};

/// The SurfaceScene of an analysed cloud: discs of radius disc_radius_factor × (distance to the 4th neighbour).
/// @throws pcsketch::Error when the cloud has no normals or the surface's neighbourhoods do not match it.
SurfaceScene build_surface_scene(const PointCloud& cloud, const differential::Surface& surface,
                                 const SurfaceSceneOptions& options = {});

/// Contours of `cloud` seen by `camera` and the visibility of those contours and of `lines` (ridges, valleys).
/// @param cloud analysed cloud (oriented normals), as left by differential::analyse_surface
/// @param surface its neighbourhoods and spacing h
/// @param scene build_surface_scene(cloud, surface), shared by every view
/// @param border empty or #P: the open scan's rims (features::Boundary::border; see find_contour_points)
/// @throws pcsketch::Error when the cloud has no normals or the surface does not match it.
ViewResult compute_view(const PointCloud& cloud, const differential::Surface& surface, const SurfaceScene& scene,
                        const std::vector<Polyline>& lines, const Camera& camera, const ViewOptions& options = {},
                        const std::vector<std::uint8_t>& border = {});

}  // namespace pcsketch::view
