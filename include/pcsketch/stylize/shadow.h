#pragma once
// Shadow regions (paper §VI): the paper's hatching between each ridge/valley line and its projection along the light
// (eqs. 12–14, graded blocks of Fig. 19), and, beyond the paper, image-space hatching of the attached shadow.

#include <cstdint>
#include <optional>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/core/report.h"
#include "pcsketch/view/camera.h"
#include "pcsketch/view/surface_scene.h"

namespace pcsketch::stylize {

/// Which shadows are drawn.
enum class ShadowMode : std::uint8_t {
  None,      ///< no shading
  Paper,     ///< §VI: hatch strokes and graded blocks between ridge/valley lines and their projection along the light
  Attached,  ///< beyond the paper: parallel image-space hatching of the visible surface facing away from the light
  Both,      ///< Paper and Attached together
};

/// The light. Directions are the way the light travels (from the light into the scene), in world axes.
struct LightOptions {
  /// Explicit travel direction (need not be unit); overrides azimuth/elevation when set.
  std::optional<Vec3f> direction;
  /// Angle between the light direction and the xoy plane, degrees (paper Fig. 13: 45°). Positive: the light travels
  /// toward +z, the paper's direction of sight, i.e. it comes from the viewer's side and lights what the viewer sees.
  float elevation_deg = 45.f;
  /// Rotation of the light's horizontal part around the z axis, degrees. 0: the light lies in the xoz plane (paper)
  /// and comes from the +x side, travelling toward −x (with the paper's camera, +x is the image's left: light from
  /// the left, shadows cast to the right, the usual illustration convention). The travel direction is
  /// (−cos e·cos a, −cos e·sin a, sin e).
  float azimuth_deg = 0.f;
  /// When true the direction (explicit or from azimuth/elevation) is read in the camera's frame as if the camera
  /// were the paper's default one (x = −right, y = up, z = forward), so the light turns with the view.
  bool follow_camera = false;
};

/// Unit travel direction of the light for this camera.
/// @throws pcsketch::Error for a zero or non-finite explicit direction.
Vec3f light_direction(const LightOptions& light, const view::Camera& camera);

struct ShadowOptions {
  /// Both: the paper's cast hatching marks ridges' shadows, the attached hatching gives round shapes (sphere, the
  /// bunny's body) the tone that ridge lines alone cannot, since smooth shapes have few ridges.
  ShadowMode mode = ShadowMode::Both;
  LightOptions light;

  // --- Paper mode (§VI, eqs. 12–14) ---
  /// k: density set of eq. 14; hatch line at t = k·d of the way from the line to its projection. The geometric
  /// spacing puts the hatch lines closer near the line.
  std::vector<float> k_set = {1.f / 16, 1.f / 8, 1.f / 4, 1.f / 2};
  /// d of eq. 14. 2 makes the largest k (1/2) reach the projected line, so the hatching spans the whole shadow
  /// (with the paper's unstated d the last line could fall short or overshoot). Lines with k·d > 1 are skipped.
  float d = 2.f;
  /// Cast from valley lines too (they cast only where the light leaves the surface there; elsewhere no hit).
  bool cast_from_valleys = true;
  /// Rays along the light start this far from the line vertex (t_near, units of h), past the vertex's own disc and
  /// its neighbours' (the self-hit rule of SurfaceScene).
  float ray_offset_factor = 3.f;
  /// A vertex whose light ray hits nothing within this distance (units of h) casts no shadow; hatch strokes break.
  float max_cast_factor = 100.f;
  /// Hatch points are tested toward the camera from this offset (units of h) so the surface they lie next to does
  /// not hide them.
  float visibility_offset_factor = 2.f;
  /// Beyond the paper: a hatch point is drawn only where the surface lies behind it as seen from the camera. The
  /// points between a line and its projection are in the air; over a step they are seen against the step's face or
  /// floor (the paper's Fig. 19 shadows), but a belly's ridge casting onto a leg put graded bands across the
  /// background between the legs. Off: the paper's region, wherever it projects.
  bool clip_to_surface = true;
  /// Hatch strokes break between two vertices whose projections lie farther apart than this many times
  /// max(h, the distance of the vertices): the shadow fell onto two different surfaces.
  float max_jump_factor = 8.f;
  float cast_hatch_width_px = 0.7f;  ///< width of the paper's hatch strokes, px
  /// Ink grey of the hatch line nearest to the feature line / farthest (0 black … 1 white): darker near the line.
  float cast_grey_near = 0.2f;
  float cast_grey_far = 0.6f;
  /// Graded blocks between successive hatch lines (Fig. 19 "area 1/2/3"): filled regions, darker near the line.
  bool shade_blocks = true;
  float block_grey_near = 0.70f;  ///< grey of the block touching the line
  float block_grey_far = 0.92f;   ///< grey of the outermost block

  // --- Attached mode (beyond the paper) ---
  /// n·l thresholds (l = light travel direction) of the hatch families: family i covers the visible surface with
  /// n·l above thresholds[i]. 0.05 starts just past the terminator (noise-free), 0.5 adds cross-hatching where the
  /// surface turns clearly away from the light.
  std::vector<float> attached_levels = {0.05f, 0.5f};
  float hatch_spacing_px = 6.f;       ///< distance between parallel hatch lines, px (readable at 1024 px, plotter-safe)
  float hatch_angle_deg = 45.f;       ///< angle of the first family, degrees counter-clockwise from the image's +u
  float cross_angle_deg = 90.f;       ///< each further family turns by this much (90: classic cross-hatching)
  float attached_width_px = 0.6f;     ///< stroke width, px
  float attached_grey_light = 0.45f;  ///< grey of the first family
  float attached_grey_dark = 0.25f;   ///< grey of the last family (deeper shadow, darker ink)
  float mask_cell_px = 2.f;           ///< cell size of the image-space shading grid, px
  /// Splatted disc radius in units of each point's local spacing (as SurfaceScene's disc_radius_factor).
  float splat_radius_factor = 1.f;
  /// Hatch lines break where the visible depth jumps by more than this (units of h): another surface begins.
  float depth_jump_factor = 4.f;
  /// Cells whose visible disc faces the viewer less than this (−n·v, v the viewing ray) are not hatched: surfaces
  /// seen at a grazing angle (beyond about 80°) are thin strips where hatching reads as specks.
  float attached_min_facing = 0.15f;
  /// Shorter hatch pieces are dropped: specks on surfaces seen edge-on read as noise. 6 px = one hatch spacing.
  float min_hatch_px = 6.f;
  ProgressFn progress;  ///< optional
};

/// What shading needs of one view.
struct ShadowInput {
  const std::vector<Vec3f>& positions;      ///< #P, relative to the cloud's origin
  const std::vector<Vec3f>& normals;        ///< #P, unit, oriented outward
  const std::vector<float>& local_spacing;  ///< #P, the radii the scene was built with (before its factor)
  const view::SurfaceScene& scene;          ///< the same points as oriented discs
  const view::Camera& camera;
  float spacing = 0.f;  ///< mean spacing h, model units
  /// Ridge and valley lines (other kinds are ignored by the paper mode).
  const std::vector<Polyline>& lines;
  /// Empty (all visible) or one entry per line, each empty or #L flags (0 = hidden); hidden vertices cast nothing.
  const std::vector<std::vector<std::uint8_t>>& visible;
};

/// Shading of one view, with counts for diagnostics.
struct ShadowResult {
  std::vector<Stroke> strokes;         ///< kind Hatch, visible, constant width, grey per family / hatch line
  std::vector<ShadeRegion> regions;    ///< paper mode's graded blocks
  Vec3f light = Vec3f::Zero();         ///< unit light travel direction used
  std::size_t cast_vertices = 0;       ///< paper mode: line vertices whose light ray found a surface
  std::size_t casting_candidates = 0;  ///< paper mode: visible ridge/valley vertices tried
  Warnings warnings;                   ///< e.g. nothing shaded because the cloud is degenerate
};

/// Shadow hatching of one view (paper §VI and the attached-shadow extension), per `options.mode`.
/// Paper mode: for each visible vertex p of a ridge (and valley) line, the ray p + t·l (t > ray_offset) finds the
/// projection p' on a surface facing the light (a hit on a disc facing away from the light means the ray travelled
/// inside the object: no shadow); n = p' − p, hatch points p_c = p + k·d·n (eqs. 12–14) kept where nothing hides
/// them from the viewer, joined along the line into hatch strokes; the blocks between successive hatch lines
/// (the line itself first) become ShadeRegions whose grey grows away from the line.
/// Attached mode: the points are splatted as oriented discs into an image grid (nearest front-facing disc per cell,
/// its n·l, lightly smoothed); hatch lines at fixed angle and spacing are clipped to the cells with n·l above each
/// family's threshold, with ends placed by interpolating n·l, and broken at depth jumps.
/// An empty or degenerate cloud (h not positive) gives no shading and a warning.
/// @throws pcsketch::Error when array sizes disagree, or for non-positive hatch spacing, mask cell or d.
ShadowResult shadow_hatching(const ShadowInput& input, const ShadowOptions& options = {});

}  // namespace pcsketch::stylize
