#pragma once
// The camera of one view: orthographic by default (the paper looks along +z), perspective on request.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string_view>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::view {

enum class Projection { Orthographic, Perspective };

/// The views of technical drawing, relative to `up` (CameraOptions::up). *front* looks horizontally along the part
/// of +z perpendicular to up (the paper's +z view when up is y), or along +x when up is along z; *right* is seen
/// from the front view's right-hand side, *left* from its left; *top* looks down along −up with the front's far
/// side up in the image (third-angle plan), *bottom* up along +up; *iso* is the isometric view from front, right
/// and above (azimuth −45°, elevation 35.26°).
enum class NamedView { Front, Back, Left, Right, Top, Bottom, Iso };

/// "front", "back", … as on the command line.
std::string_view to_string(NamedView view);
/// The view of that name, or nothing.
std::optional<NamedView> parse_named_view(std::string_view name);

/// The three-quarter view (azimuth −35°, elevation 15°: from the front's right, a little above) that the CLI takes
/// when `--up` is given without a view.
inline constexpr double kThreeQuarterAzimuthDeg = -35.0;
inline constexpr double kThreeQuarterElevationDeg = 15.0;

/// How the user describes a view. Every field has a default so that `CameraOptions{}` is the paper's view. At most
/// one of `direction`, `named`, azimuth/elevation and eye with target sets the direction of sight (validate.h
/// refuses two).
struct CameraOptions {
  Projection projection = Projection::Orthographic;
  /// Direction of sight, world units. Unset: the paper's +z (unless another field sets the sight).
  std::optional<Vec3d> direction;
  /// A named view relative to `up`.
  std::optional<NamedView> named;
  /// Up hint: the image's up is its part perpendicular to the sight. An explicit direction parallel to it is
  /// refused by validate(); make_camera() then takes the world axis least aligned with the sight.
  Vec3d up{0, 1, 0};
  /// Alternative to `direction`: viewer's azimuth around `up` and elevation above the horizon, in degrees.
  /// Azimuth 0, elevation 0 is the front view (+z when up is y); positive azimuth turns toward the left view,
  /// positive elevation looks down on the model. At ±90° elevation the image's up is the front's far side.
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

/// The direction of sight the options describe (not normalised) and the up hint that goes with it: the options' up,
/// or for azimuth/elevation and named views the up tilted with the elevation (defined when looking along up).
struct SightFrame {
  Vec3d forward;
  Vec3d up;
};
SightFrame sight_frame(const CameraOptions& options);

/// Builds the camera for `positions` (relative to `origin`) and frames their projection inside the image with
/// the margin. Throws pcsketch::Error for a zero direction, a non-positive size or fov outside (0, 180).
Camera make_camera(const std::vector<Vec3f>& positions, const Vec3d& origin, const CameraOptions& options = {});

}  // namespace pcsketch::view
