#include "pcsketch/view/view.h"

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>

#include "core/progress.h"
#include "pcsketch/core/error.h"
#include "pcsketch/features/boundary_lines.h"

namespace pcsketch::view {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void check_analysed(const PointCloud& cloud, const differential::Surface& surface, const char* where) {
  if (!cloud.has_normals())
    throw Error(std::string(where) + ": the cloud has no normals (run differential::analyse_surface first)");
  if (surface.neighbourhoods.size() != cloud.size())
    throw Error(std::string(where) + ": the surface's neighbourhoods do not match the cloud (analyse this cloud)");
  if (!(surface.spacing > 0)) throw Error(std::string(where) + ": the surface's mean spacing h must be positive");
}

}  // namespace

SurfaceScene build_surface_scene(const PointCloud& cloud, const differential::Surface& surface,
                                 const SurfaceSceneOptions& options) {
  check_analysed(cloud, surface, "surface scene");
  return SurfaceScene(cloud.positions, cloud.normals, local_spacing(surface.neighbourhoods), options);
}

ViewResult compute_view(const PointCloud& cloud, const differential::Surface& surface, const SurfaceScene& scene,
                        const std::vector<Polyline>& lines, const Camera& camera, const ViewOptions& options,
                        const std::vector<std::uint8_t>& border) {
  check_analysed(cloud, surface, "view");
  ViewResult result;
  result.camera = camera;

  auto start = std::chrono::steady_clock::now();
  const ContourOptions contour_options = pcsketch::detail::with_progress(options.contours, options.progress);
  result.contour_points = find_contour_points(cloud.positions, cloud.normals, surface.neighbourhoods, surface.spacing,
                                              camera, contour_options, surface.normal_noise, border, surface.denoised);
  result.timings.contour_points = seconds_since(start);

  start = std::chrono::steady_clock::now();
  ContourLines contours = connect_contours(result.contour_points, cloud.positions, surface.spacing, contour_options,
                                           surface.denoised);
  result.timings.contour_connection = seconds_since(start);
  result.contour_count = contours.outline.size() + contours.interior.size();
  result.outline_count = contours.outline.size();
  // An open sheet seen face-on has no outline but its border (a boundary line).
  const bool open_scan = std::find(border.begin(), border.end(), features::Boundary::kDrawnRim) != border.end();
  if (contours.outline.empty() && !cloud.empty() && !open_scan)
    result.warnings.push_back("view: no outline found (is the whole cloud behind the camera?)");

  start = std::chrono::steady_clock::now();
  for (const Polyline& line : contours.outline) result.lines.push_back(seen_line(line, camera));
  std::vector<Polyline> cast = std::move(contours.interior);
  cast.insert(cast.end(), lines.begin(), lines.end());
  std::vector<ViewLine> seen = line_visibility(cast, scene, camera, surface.spacing,
                                               pcsketch::detail::with_progress(options.visibility, options.progress));
  result.lines.insert(result.lines.end(), std::make_move_iterator(seen.begin()), std::make_move_iterator(seen.end()));
  result.timings.visibility = seconds_since(start);
  return result;
}

}  // namespace pcsketch::view
