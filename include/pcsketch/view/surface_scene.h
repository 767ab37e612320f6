#pragma once
// The cloud as a ray-traceable surface: every point an oriented disc (Embree's ORIENTED_DISC_POINT geometry).
// Built once per cloud; used for visibility (rays toward the viewer) and shadows (rays along the light).

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::view {

struct SurfaceSceneOptions {
  /// Disc radius in units of the local spacing (distance to the point's k-th neighbour, see `local_spacing`). Discs
  /// must overlap to close the surface; 1.0 leaves no holes on uniform scans while keeping silhouettes within about h.
  float disc_radius_factor = 1.0f;
  ProgressFn progress;  ///< optional: the build reports as "scene" (from Embree's threads, one call at a time)
};

/// A hit of a ray with the disc of one point.
struct SurfaceHit {
  float t = 0;              ///< distance along the (unit) ray direction
  std::uint32_t point = 0;  ///< index of the point whose disc was hit
  Vec3f normal = Vec3f::UnitZ();  ///< unit normal of that disc
};

/// One point's disc as the scene holds it.
struct SurfaceDisc {
  Vec3f centre = Vec3f::Zero();   ///< the point, relative coordinates
  Vec3f normal = Vec3f::UnitZ();  ///< unit normal (UnitZ for a point without a usable normal)
  float radius = 0;               ///< model units; 0 for a point without a usable normal (never hit)
};

/// Each point's local spacing: the distance to its `kth` nearest neighbour (1-based, clamped to the neighbourhood
/// size). With kth = 4 discs of that radius cover a randomly sampled surface without holes (a disc of the 4th
/// neighbour distance holds about 4 points), where the nearest-neighbour distance leaves gaps in sparse spots.
/// @return #P radii, model units.
std::vector<float> local_spacing(const neighbourhood::Neighbourhoods& neighbourhoods, std::size_t kth = 4);

/// Ray queries against the points as oriented discs. Const queries are thread-safe.
///
/// Self-hit rule: a disc contains its own point, so a ray leaving a cloud point p hits p's disc at t = 0 and, near a
/// silhouette where the ray grazes the surface, the discs of p's neighbours at t up to about twice their radius.
/// Embree only ignores hits with t < t_near, so callers tracing from a cloud point must pass a t_near offset of a few
/// local spacings (visibility uses `VisibilityOptions::self_offset_factor`); t_near = 0 counts p's own disc as a hit.
/// Points without a finite non-zero normal get a zero radius and are never hit; `SurfaceHit::point` is the index
/// into the arrays given to the constructor.
class SurfaceScene {
 public:
  /// `local_spacing` is #P (each point's disc radius before the factor, see `local_spacing()`); positions/normals
  /// are #P, normals unit (they are normalised again). Throws pcsketch::Error on mismatched sizes or Embree failure.
  SurfaceScene(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
               const std::vector<float>& local_spacing, const SurfaceSceneOptions& options = {});
  ~SurfaceScene();
  SurfaceScene(SurfaceScene&&) noexcept;
  SurfaceScene& operator=(SurfaceScene&&) noexcept;

  /// First disc hit by the ray origin + t·direction (direction unit), t in (t_near, t_far).
  std::optional<SurfaceHit> intersect(const Vec3f& origin, const Vec3f& direction, float t_near, float t_far) const;
  /// Whether any disc is hit with t in (t_near, t_far); cheaper than intersect.
  bool occluded(const Vec3f& origin, const Vec3f& direction, float t_near, float t_far) const;

  /// Number of points (discs), as given to the constructor.
  std::size_t size() const;
  /// The disc of point `point` (< size()), read from the scene's own buffers (no copy of the cloud is kept).
  SurfaceDisc disc(std::uint32_t point) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcsketch::view
