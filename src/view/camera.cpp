#include "pcsketch/view/camera.h"

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>

#include "pcsketch/core/error.h"

namespace pcsketch::view {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Each named view as (azimuth, elevation) in degrees; the isometric elevation is atan(1/√2).
constexpr std::array<std::pair<std::string_view, std::array<double, 2>>, 7> kNamedViews{{
    {"front", {0, 0}},
    {"back", {180, 0}},
    {"left", {90, 0}},
    {"right", {-90, 0}},
    {"top", {0, 90}},
    {"bottom", {0, -90}},
    {"iso", {-45, 35.26438968275465}},
}};

/// Sight and image up of the viewer at azimuth `a` around `up` and elevation `e`, degrees: in a frame whose y axis is
/// `up`, so that azimuth turns around the user's up.
SightFrame orbit(const Vec3d& up_hint, double azimuth_deg, double elevation_deg) {
  const double a = azimuth_deg * kPi / 180.0, e = elevation_deg * kPi / 180.0;
  const Vec3d up = (up_hint / up_hint.cwiseAbs().maxCoeff()).normalized();
  Vec3d z = Vec3d::UnitZ() - up.z() * up;
  if (z.norm() < 1e-6) z = Vec3d::UnitX() - up.x() * up;
  z.normalize();
  const Vec3d x = up.cross(z);
  const Vec3d horizontal = -std::sin(a) * x + std::cos(a) * z;
  // The image's up leans back with the elevation, so that it stays defined when looking straight down or up.
  return {std::cos(e) * horizontal - std::sin(e) * up, std::sin(e) * horizontal + std::cos(e) * up};
}

}  // namespace

std::string_view to_string(NamedView view) { return kNamedViews[static_cast<std::size_t>(view)].first; }

std::optional<NamedView> parse_named_view(std::string_view name) {
  for (std::size_t i = 0; i < kNamedViews.size(); ++i)
    if (kNamedViews[i].first == name) return static_cast<NamedView>(i);
  return std::nullopt;
}

SightFrame sight_frame(const CameraOptions& o) {
  if (o.eye && o.target) return {*o.target - *o.eye, o.up};
  if (o.named) {
    const auto& [azimuth, elevation] = kNamedViews[static_cast<std::size_t>(*o.named)].second;
    return orbit(o.up, azimuth, elevation);
  }
  if (o.azimuth_deg || o.elevation_deg) return orbit(o.up, o.azimuth_deg.value_or(0.0), o.elevation_deg.value_or(0.0));
  return {o.direction.value_or(Vec3d::UnitZ()), o.up};
}

Camera make_camera(const std::vector<Vec3f>& positions, const Vec3d& origin, const CameraOptions& o) {
  if (o.width <= 0 || o.height <= 0) throw Error("camera: image size must be positive");
  if (o.projection == Projection::Perspective && !(o.fov_deg > 0 && o.fov_deg < 180))
    throw Error("camera: field of view must be in (0, 180) degrees");
  const SightFrame frame = sight_frame(o);
  const Vec3d& dir = frame.forward;
  if (!dir.allFinite() || !(dir.cwiseAbs().maxCoeff() > 1e-12))
    throw Error("camera: view direction must be a non-zero vector");
  if (o.eye && o.target && o.projection == Projection::Orthographic && (*o.eye - *o.target).norm() == 0)
    throw Error("camera: eye and target coincide");

  Camera cam;
  cam.projection = o.projection;
  cam.width = o.width;
  cam.height = o.height;
  cam.origin = origin;
  // Scaled by the largest coordinate first: the norm of (1e308, 1e308, 1e308) overflows and would give a zero axis.
  const Vec3d f = (dir / dir.cwiseAbs().maxCoeff()).normalized();
  const Vec3d up_hint =
      frame.up.cwiseAbs().maxCoeff() > 0 ? Vec3d(frame.up / frame.up.cwiseAbs().maxCoeff()) : frame.up;
  Vec3d up = up_hint - up_hint.dot(f) * f;
  if (up.norm() < 1e-6 * std::max(1.0, up_hint.norm())) {
    // The up hint is parallel to the sight: take the world axis least aligned with it.
    Eigen::Index axis = 0;
    f.cwiseAbs().minCoeff(&axis);
    up = Vec3d::Unit(axis) - f[axis] * f;
  }
  up.normalize();
  cam.forward = f.cast<float>();
  cam.up = up.cast<float>();
  cam.right = f.cross(up).cast<float>();

  const Box3f box = bounding_box(positions);
  const Vec3f center = box.empty() ? Vec3f::Zero() : box.center();
  const float radius = std::max(0.5f * box.diagonal(), 1e-6f);
  const float margin_px = static_cast<float>(o.margin * std::min(o.width, o.height));
  const float avail_w = std::max(1.f, static_cast<float>(o.width) - 2 * margin_px);
  const float avail_h = std::max(1.f, static_cast<float>(o.height) - 2 * margin_px);

  if (o.projection == Projection::Orthographic) {
    cam.eye = center - cam.forward * (2.f * radius);
  } else if (o.eye) {
    cam.eye = (*o.eye - origin).cast<float>();
  } else {
    const double half = 0.5 * o.fov_deg * kPi / 180.0;
    cam.eye = center - cam.forward * static_cast<float>(radius / std::sin(half));
  }

  // Extent of the projection in camera coordinates (orthographic: units; perspective: tangents).
  Vec2f lo = Vec2f::Constant(std::numeric_limits<float>::max()), hi = -lo;
  for (const Vec3f& p : positions) {
    const Vec3f d = p - cam.eye;
    const float depth = d.dot(cam.forward);
    Vec2f q(d.dot(cam.right), d.dot(cam.up));
    if (o.projection == Projection::Perspective) {
      if (depth <= 1e-6f * radius) continue;  // behind the eye: not framed
      q /= depth;
    }
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  if (lo.x() > hi.x()) lo = hi = Vec2f::Zero();
  const Vec2f ext = (hi - lo).cwiseMax(Vec2f::Constant(1e-12f));
  if (o.projection == Projection::Perspective && !o.eye) {
    // Focal length from the field of view keeps the perspective the user asked for; framing only re-centres.
    cam.scale = static_cast<float>(0.5 * o.height / std::tan(0.5 * o.fov_deg * kPi / 180.0));
  } else {
    cam.scale = std::min(avail_w / ext.x(), avail_h / ext.y());
  }
  if (o.projection == Projection::Perspective && o.target && o.eye) {
    cam.principal = Vec2f(0.5f * static_cast<float>(o.width), 0.5f * static_cast<float>(o.height));
  } else {
    const Vec2f mid = 0.5f * (lo + hi);
    cam.principal = Vec2f(0.5f * static_cast<float>(o.width) - cam.scale * mid.x(),
                          0.5f * static_cast<float>(o.height) + cam.scale * mid.y());
  }
  return cam;
}

Vec3f Camera::project(const Vec3f& p) const {
  const Vec3f d = p - eye;
  const float depth = d.dot(forward);
  Vec2f q(d.dot(right), d.dot(up));
  if (projection == Projection::Perspective) q /= std::max(depth, 1e-12f);
  return {principal.x() + scale * q.x(), principal.y() - scale * q.y(), depth};
}

Vec3f Camera::ray_direction(const Vec3f& p) const {
  if (projection == Projection::Orthographic) return forward;
  return (p - eye).normalized();
}

Vec3f Camera::ray_origin(const Vec3f& p) const {
  if (projection == Projection::Perspective) return eye;
  return p - forward * (p - eye).dot(forward);
}

float Camera::units_per_pixel(float depth) const {
  return projection == Projection::Orthographic ? 1.f / scale : std::max(depth, 0.f) / scale;
}

nlohmann::json Camera::to_json() const {
  auto vec = [](const Vec3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  return {{"projection", projection == Projection::Orthographic ? "orthographic" : "perspective"},
          {"direction", vec(forward.cast<double>())},
          {"up", vec(up.cast<double>())},
          {"right", vec(right.cast<double>())},
          {"eye", vec(origin + eye.cast<double>())},
          {"scale", scale},
          {"scale_unit", projection == Projection::Orthographic ? "pixels per model unit" : "focal length in pixels"},
          {"principal_point", {principal.x(), principal.y()}},
          {"width", width},
          {"height", height}};
}

}  // namespace pcsketch::view
