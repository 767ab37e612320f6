#pragma once
// The camera of one view: orthographic by default (the paper looks along +z), perspective on request.

#include <nlohmann/json_fwd.hpp>
#include <optional>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::view {

enum class Projection { Orthographic, Perspective };

/// How the user describes a view. Every field has a default so that `CameraOptions{}` is the paper's view.
struct CameraOptions {
  Projection projection = Projection::Orthographic;
  /// Direction of sight, world units (paper: +z). Ignored when azimuth/elevation or eye/target are set.
  Vec3d direction{0, 0, 1};
  /// Up hint; projected to be perpendicular to the direction. If parallel to it, another axis is chosen.
  Vec3d up{0, 1, 0};
  /// Alternative to `direction`: viewer's azimuth around `up` and elevation above the horizon, in degrees.
  /// Azimuth 0, elevation 0 looks along +z; positive elevation looks down on the model.
  std::optional<double> azimuth_deg;
  std::optional<double> elevation_deg;
  /// Perspective only: eye and target points in world coordinates. Default: the target is the box centre and the
  /// eye stands back along `direction` far enough for the bounding sphere to fit the field of view.
  std::optional<Vec3d> eye;
  std::optional<Vec3d> target;
  double fov_deg = 35.0;  ///< perspective only: vertical field of view, degrees
  int width = 1024;       ///< image size in pixels
  int height = 1024;
  double margin = 0.05;   ///< empty border around the framed cloud, as a fraction of the smaller image side
};

/// A resolved camera, in the cloud's relative coordinates. Image coordinates are pixels, origin top-left, v down.
struct Camera {
  Projection projection = Projection::Orthographic;
  Vec3f eye = Vec3f::Zero();      ///< perspective: centre of projection; orthographic: a point on the near side
  Vec3f forward{0, 0, 1};         ///< unit direction of sight
  Vec3f right{-1, 0, 0};          ///< unit image +u direction (forward × up)
  Vec3f up{0, 1, 0};              ///< unit image −v direction
  float scale = 1.f;              ///< orthographic: pixels per model unit; perspective: focal length in pixels
  Vec2f principal{512.f, 512.f};  ///< image position of the optical axis / of `eye` (orthographic)
  int width = 1024;
  int height = 1024;
  Vec3d origin = Vec3d::Zero();   ///< the cloud's origin, to report the camera in world coordinates

  /// (u, v, depth): pixel position and depth along `forward` from `eye` (larger is farther).
  Vec3f project(const Vec3f& p) const;
  /// Unit direction of the ray from the viewer through p (orthographic: `forward`).
  Vec3f ray_direction(const Vec3f& p) const;
  /// Origin of the viewing ray that passes through p (orthographic: p moved back to the eye plane).
  Vec3f ray_origin(const Vec3f& p) const;
  /// Model units per pixel at depth `depth` (for orthographic independent of depth).
  float units_per_pixel(float depth) const;
  /// Everything needed to reproduce the view, in world coordinates.
  nlohmann::json to_json() const;
};

/// Builds the camera for `positions` (relative to `origin`) and frames their projection inside the image with
/// the margin. Throws pcsketch::Error for a zero direction, a non-positive size or fov outside (0, 180).
Camera make_camera(const std::vector<Vec3f>& positions, const Vec3d& origin, const CameraOptions& options = {});

}  // namespace pcsketch::view
