#pragma once
// Shared set-up of the view tests: a cloud with exact normals plus the view-independent data a view needs.

#include "pcsketch/differential/surface.h"
#include "pcsketch/neighbourhood/kd_tree.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/neighbourhood/spacing.h"
#include "pcsketch/view/view.h"

namespace pcsketch::view::testing {

/// Neighbourhoods and spacing of a cloud whose normals are already exact (analytic shapes): the Surface a view
/// needs, without estimating normals, so view tests only test the view.
inline differential::Surface exact_surface(const PointCloud& cloud, std::size_t k = 16) {
  const neighbourhood::KdTree tree(cloud.positions);
  differential::Surface surface;
  surface.neighbourhoods = neighbourhood::compute_neighbourhoods(tree, cloud.positions, {.k = k});
  surface.spacing = neighbourhood::mean_spacing(surface.neighbourhoods);
  return surface;
}

/// Everything one view of a cloud needs, built once.
struct Analysed {
  PointCloud cloud;
  differential::Surface surface;
  SurfaceScene scene;

  explicit Analysed(PointCloud c)
      : cloud(std::move(c)), surface(exact_surface(cloud)), scene(build_surface_scene(cloud, surface)) {}

  ViewResult view(const CameraOptions& camera_options, const std::vector<Polyline>& lines = {},
                  const ViewOptions& options = {}) const {
    const Camera camera = make_camera(cloud.positions, cloud.origin, camera_options);
    return compute_view(cloud, surface, scene, lines, camera, options);
  }
};

}  // namespace pcsketch::view::testing
