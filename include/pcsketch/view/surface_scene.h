#pragma once
// The cloud as a ray-traceable surface: every point an oriented disc (Embree's ORIENTED_DISC_POINT geometry).
// Built once per cloud; used for visibility (rays toward the viewer) and shadows (rays along the light).

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::view {

struct SurfaceSceneOptions {
  /// Disc radius in units of the local spacing (distance to the point's k-th neighbour, see `build`). Discs must
  /// overlap to close the surface; 1.0 leaves no holes on uniform scans while keeping silhouettes within about h.
  float disc_radius_factor = 1.0f;
};

/// A hit of a ray with the disc of one point.
struct SurfaceHit {
  float t = 0;              ///< distance along the (unit) ray direction
  std::uint32_t point = 0;  ///< index of the point whose disc was hit
};

/// Ray queries against the points as oriented discs. Const queries are thread-safe.
class SurfaceScene {
 public:
  /// `local_spacing` is #P (each point's disc radius before the factor); positions/normals are #P.
  SurfaceScene(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
               const std::vector<float>& local_spacing, const SurfaceSceneOptions& options = {});
  ~SurfaceScene();
  SurfaceScene(SurfaceScene&&) noexcept;
  SurfaceScene& operator=(SurfaceScene&&) noexcept;

  /// First disc hit by the ray origin + t·direction (direction unit), t in (t_near, t_far).
  std::optional<SurfaceHit> intersect(const Vec3f& origin, const Vec3f& direction, float t_near, float t_far) const;
  /// Whether any disc is hit with t in (t_near, t_far); cheaper than intersect.
  bool occluded(const Vec3f& origin, const Vec3f& direction, float t_near, float t_far) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcsketch::view
