#include "pcsketch/validate.h"

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/view/camera.h"

namespace pcsketch {

namespace {

constexpr double kHuge = std::numeric_limits<double>::max();

/// `value` must be finite and in [lo, hi], or in (lo, hi] when `above` is set (a strictly positive length).
void in_range(const std::string& flag, double value, double lo, double hi, bool above = false) {
  const bool ok = std::isfinite(value) && (above ? value > lo : value >= lo) && value <= hi;
  if (ok) return;
  if (!std::isfinite(value)) throw OptionError(flag, "must be a finite number, got " + number(value));
  const std::string range = (above ? "(" : "[") + number(lo) + ", " + (hi == kHuge ? "inf)" : number(hi) + "]");
  throw OptionError(flag, "must be in " + range + ", got " + number(value));
}
/// `value` in the open interval (lo, hi).
void open_range(const std::string& flag, double value, double lo, double hi) {
  in_range(flag, value, -kHuge, kHuge);  // the message for NaN and Inf
  if (!(value > lo && value < hi))
    throw OptionError(flag, "must be in (" + number(lo) + ", " + number(hi) + "), got " + number(value));
}
void positive(const std::string& flag, double value, double hi = kHuge) { in_range(flag, value, 0, hi, true); }
void non_negative(const std::string& flag, double value, double hi = kHuge) { in_range(flag, value, 0, hi); }
void fraction(const std::string& flag, double value) { in_range(flag, value, 0, 1); }

/// A direction: finite and non-zero (any length; the camera scales it before normalising).
void direction(const std::string& flag, const Vec3d& v) {
  if (!v.allFinite()) throw OptionError(flag, "must be three finite numbers");
  if (v.cwiseAbs().maxCoeff() == 0) throw OptionError(flag, "must be a non-zero vector");
}

std::string vec_text(const Vec3d& v) { return number(v.x()) + "," + number(v.y()) + "," + number(v.z()); }

/// A point: finite, and near enough for float image coordinates (the camera JSON held null from 1e30 on).
void point(const std::string& flag, const Vec3d& v) {
  if (!v.allFinite() || v.cwiseAbs().maxCoeff() > 1e15)
    throw OptionError(flag, "must be three finite numbers of magnitude at most 1e15");
}

/// One way of choosing the direction of sight: `--view X,Y,Z`, `--view NAME`, `--azimuth/--elevation` or
/// `--eye` with `--target`; two would silently ignore one.
void one_sight(const view::CameraOptions& c) {
  std::vector<std::string> given;
  if (c.direction) given.emplace_back("--view X,Y,Z");
  if (c.named) given.push_back("--view " + std::string(view::to_string(*c.named)));
  if (c.azimuth_deg || c.elevation_deg) given.emplace_back(c.azimuth_deg ? "--azimuth" : "--elevation");
  if (c.eye && c.target) given.emplace_back("--eye/--target");
  if (given.size() > 1)
    throw OptionError(given[0].substr(0, given[0].find(' ')),
                      "conflicts with " + given[1] + ": both set the direction of sight, give one");
}

/// A sight parallel to up leaves the image without an up direction (named and azimuth/elevation views define it).
void sight_not_along_up(const view::CameraOptions& c) {
  if (c.named || c.azimuth_deg || c.elevation_deg) return;
  const Vec3d f = view::sight_frame(c).forward;
  const Vec3d sight = f / f.cwiseAbs().maxCoeff(), up = c.up / c.up.cwiseAbs().maxCoeff();
  if (sight.normalized().cross(up.normalized()).norm() > 1e-6) return;
  const std::string flag = c.eye && c.target ? "--eye/--target" : c.direction ? "--view" : "--up";
  const std::string what = c.eye && c.target ? "the sight from --eye to --target"
                           : c.direction     ? "the direction of sight"
                                             : "the default direction of sight +z";
  throw OptionError(flag, what + " is parallel to --up " + vec_text(c.up) +
                              ": the image has no up direction (give another --view, a named view or --azimuth)");
}

void validate_camera(const view::CameraOptions& c) {
  if (c.direction) direction("--view", *c.direction);
  direction("--up", c.up);
  if (c.azimuth_deg) in_range("--azimuth", *c.azimuth_deg, -1e6, 1e6);
  if (c.elevation_deg) in_range("--elevation", *c.elevation_deg, -1e6, 1e6);
  if (c.eye) point("--eye", *c.eye);
  if (c.target) point("--target", *c.target);
  if (c.eye && c.target && *c.eye == *c.target) throw OptionError("--eye", "must differ from --target");
  open_range("--fov", c.fov_deg, 0, 180);
  in_range("--size", c.width, 1, kMaxImageSide);
  in_range("--size", c.height, 1, kMaxImageSide);
  in_range("--margin", c.margin, 0, 0.45);
  one_sight(c);
  sight_not_along_up(c);
}

void validate_surface(const differential::SurfaceOptions& s) {
  in_range("--neighbours", static_cast<double>(s.neighbourhood.k), 3, neighbourhood::kMaxNeighbours);
  in_range("surface.normals.k", static_cast<double>(s.normals.k), 0, neighbourhood::kMaxNeighbours);
  in_range("surface.orientation.k", static_cast<double>(s.orientation.k), 0, neighbourhood::kMaxNeighbours);
  in_range("surface.curvature.k", static_cast<double>(s.curvature.k), 0, neighbourhood::kMaxNeighbours);
  in_range("surface.curvature.max_k", static_cast<double>(s.curvature.max_k), 0, 2 * neighbourhood::kMaxNeighbours);
  non_negative("surface.curvature.noise_tolerance", s.curvature.noise_tolerance);
  fraction("--file-normals (disagreement)", s.file_normal_disagreement);
}

/// The names (flags or option paths) of the tracing and joining options, in the order validate_lines checks them.
using LineOptionNames = std::array<const char*, 10>;

/// Tracing and joining of ridge/valley lines and of boundary lines share their options.
void validate_lines(const features::TraceOptions& t, const features::JoinOptions& j, const LineOptionNames& name) {
  positive(name[0], t.radius_factor, 1e4);
  if (t.radius) positive(name[1], *t.radius);
  in_range(name[2], t.corridor_fraction, 0, 1, true);
  in_range(name[3], t.max_turn_deg, 0, 90, true);
  non_negative(name[4], j.join_distance_alpha, 1e4);
  in_range(name[5], j.join_angle_beta_deg, 0, 90);
  non_negative(name[6], j.min_length_factor);
  if (j.min_length) non_negative(name[7], *j.min_length);
  in_range(name[8], j.smoothing_iterations, 0, 100);
  fraction(name[9], j.smoothing_weight);
}

void validate_features(const features::RidgeValleyOptions& f) {
  const features::DetectionOptions& d = f.detection;
  // α = 0 would make every point a ridge/valley point (and fail late); it must be a positive fraction.
  open_range("--alpha", d.ridge_threshold_alpha, 0, 1);
  in_range("--extreme-percentile", d.extreme_percentile, 0, 100, true);
  non_negative("--saliency-floor", d.saliency_floor);
  non_negative("--median-factor", d.median_factor);
  open_range("--suppression-cone", d.suppression_cone_deg, 0, 90);
  validate_lines(f.tracing, f.joining,
                 {"--radius", "--radius-abs", "--corridor", "--max-turn", "--join-distance", "--beta", "--min-length",
                  "--min-length-abs", "--smooth", "--smooth-weight"});
}

void validate_boundary(const features::BoundaryOptions& b) {
  open_range("--boundary-gap", b.gap_threshold_deg, 0, 360);
  in_range("boundary.fold_deg", b.fold_deg, 0, 90, true);
  in_range("boundary.confirm_factor", b.confirm_factor, 1, 1e3);
  open_range("boundary.confirm_half_angle_deg", b.confirm_half_angle_deg, 0, 90);
  non_negative("--boundary-min-size", b.min_size_factor, 1e6);
  validate_lines(b.tracing, b.joining,
                 {"--boundary-radius", "boundary.tracing.radius", "boundary.tracing.corridor_fraction",
                  "boundary.tracing.max_turn_deg", "boundary.joining.join_distance_alpha",
                  "boundary.joining.join_angle_beta_deg", "boundary.joining.min_length_factor",
                  "boundary.joining.min_length", "boundary.joining.smoothing_iterations",
                  "boundary.joining.smoothing_weight"});
}

void validate_view(const view::ViewOptions& v, const view::SurfaceSceneOptions& scene) {
  const view::ContourOptions& c = v.contours;
  positive("--contour-radius", c.radius_factor, 1e3);
  in_range("view.contours.k", static_cast<double>(c.k), 1, neighbourhood::kMaxNeighbours);
  in_range("view.contours.gap_threshold_deg", c.gap_threshold_deg, 0, 360, true);
  positive("view.contours.confirm_factor", c.confirm_factor, 1e3);
  in_range("view.contours.confirm_half_angle_deg", c.confirm_half_angle_deg, 0, 180, true);
  positive("view.contours.trace_radius_factor", c.trace_radius_factor, 1e3);
  positive("--z-max", c.z_max_factor, 1e3);
  in_range("view.contours.max_turn_deg", c.max_turn_deg, 0, 180, true);
  non_negative("view.contours.absorb_factor", c.absorb_factor, 1e3);
  in_range("view.contours.heading_steps", static_cast<double>(c.heading_steps), 1, 1000);
  non_negative("view.contours.min_length_factor", c.min_length_factor);
  non_negative("--denoised-contour-length", c.denoised_min_length_factor, 1e6);
  in_range("view.contours.interior_neighbours", static_cast<double>(c.interior_neighbours), 1,
           neighbourhood::kMaxNeighbours);
  positive("view.contours.interior_dedupe_factor", c.interior_dedupe_factor, 1e3);
  positive("view.contours.interior_trace_radius_factor", c.interior_trace_radius_factor, 1e3);
  positive("view.contours.interior_z_max_factor", c.interior_z_max_factor, 1e3);
  const view::VisibilityOptions& s = v.visibility;
  non_negative("--self-offset", s.self_offset_factor, 1e3);
  fraction("view.visibility.grazing_cos", s.grazing_cos);
  non_negative("view.visibility.grazing_range_factor", s.grazing_range_factor, 1e4);
  if (s.smoothing_window % 2 == 0 || s.smoothing_window > 101)
    throw OptionError("view.visibility.smoothing_window", "must be odd and at most 101");
  in_range("view.visibility.transition_refinement", s.transition_refinement, 0, 30);
  positive("scene.disc_radius_factor", scene.disc_radius_factor, 1e3);
}

void validate_thickness(const stylize::ThicknessOptions& t) {
  non_negative("--rho-min", t.rho_min, 1e3);
  non_negative("--rho-max", t.rho_max, 1e3);
  if (t.rho_min > t.rho_max) throw OptionError("--rho-min", "must not exceed --rho-max (" + number(t.rho_max) + ")");
  non_negative("--cofi", t.cofi, 1e3);
  fraction("thickness.angle_weight", t.angle_weight);
  positive("thickness.angle_arm_px", t.angle_arm_px, 1e5);
  if (t.depth_range) {
    in_range("thickness.depth_range.near", t.depth_range->near, -kHuge, kHuge);
    in_range("thickness.depth_range.far", t.depth_range->far, -kHuge, kHuge);
  }
  non_negative("thickness.brush_taper_px", t.brush_taper_px, 1e5);
  fraction("thickness.brush_end_fraction", t.brush_end_fraction);
}

void validate_finish(const stylize::FinishOptions& f, const stylize::FusionOptions& u) {
  in_range("finish.smooth_passes", f.smooth_passes, 0, 100);
  in_range("finish.corner_angle_deg", f.corner_angle_deg, 0, 180);
  non_negative("finish.corner_arm_px", f.corner_arm_px, 1e5);
  non_negative("--min-stroke-length", f.min_length_px, 1e5);
  non_negative("finish.join_px", f.join_px, 1e5);
  non_negative("--fusion-distance", u.distance_widths, 1e3);
  non_negative("--fusion-min-stretch", u.min_stretch_px, 1e5);
  non_negative("fusion.max_gap_px", u.max_gap_px, 1e5);
  in_range("fusion.max_angle_deg", u.max_angle_deg, 0, 90);
}

void validate_shadow(const stylize::ShadowOptions& s) {
  if (s.light.direction) direction("--light", s.light.direction->cast<double>());
  // Embree aborts on rays with NaN directions: a light angle must be finite.
  in_range("--light-elevation", s.light.elevation_deg, -1e6, 1e6);
  in_range("--light-azimuth", s.light.azimuth_deg, -1e6, 1e6);
  if (s.k_set.empty()) throw OptionError("--shadow-k", "needs at least one value");
  for (const float k : s.k_set) positive("--shadow-k", k, 1e3);
  positive("--shadow-d", s.d, 1e4);
  non_negative("shadow.ray_offset_factor", s.ray_offset_factor, 1e4);
  positive("shadow.max_cast_factor", s.max_cast_factor, 1e6);
  non_negative("shadow.visibility_offset_factor", s.visibility_offset_factor, 1e4);
  positive("shadow.max_jump_factor", s.max_jump_factor, 1e6);
  non_negative("shadow.cast_hatch_width_px", s.cast_hatch_width_px, 1e3);
  for (const float grey : {s.cast_grey_near, s.cast_grey_far, s.block_grey_near, s.block_grey_far,
                           s.attached_grey_light, s.attached_grey_dark})
    fraction("shadow grey levels", grey);
  for (const float level : s.attached_levels) in_range("shadow.attached_levels", level, -1, 1);
  // Each hatch line is a path in the output: spacing bounds the output size (0.001 px made a 129 MB SVG).
  in_range("--hatch-spacing", s.hatch_spacing_px, kMinHatchSpacingPx, 1e5);
  in_range("shadow.hatch_angle_deg", s.hatch_angle_deg, -360, 360);
  in_range("shadow.cross_angle_deg", s.cross_angle_deg, -360, 360);
  non_negative("shadow.attached_width_px", s.attached_width_px, 1e3);
  in_range("shadow.mask_cell_px", s.mask_cell_px, 0.5, 1e4);
  positive("shadow.splat_radius_factor", s.splat_radius_factor, 1e3);
  positive("shadow.depth_jump_factor", s.depth_jump_factor, 1e6);
  fraction("shadow.attached_min_facing", s.attached_min_facing);
  non_negative("shadow.min_hatch_px", s.min_hatch_px, 1e6);
}

void validate_render(const render::RenderOptions& r) {
  if (r.pen_width) positive("--pen-width-px", *r.pen_width, 1e3);
  positive("--pen-width-mm", r.pen_width_mm, 100);
  positive("render.default_width", r.default_width, 1e3);
  non_negative("render.width_step", r.width_step, 1e3);
  positive("render.hidden_width", r.hidden_width, 1e3);
  fraction("render.hidden_grey", r.hidden_grey);
  positive("render.hidden_dash", r.hidden_dash, 1e5);
  if (r.page_width_mm) positive("--page-width-mm", *r.page_width_mm, 1e5);
  in_range("render.decimals", r.decimals, 0, 6);
}

void validate_plotter(const plotter::PlotterOptions& p) {
  non_negative("--merge-tolerance-mm", p.merge_tolerance_mm, 100);
  non_negative("plotter.collinear_tolerance_mm", p.collinear_tolerance_mm, 100);
  non_negative("--min-stroke-mm", p.min_stroke_mm, 1e4);
}

/// A stated scale needs the model's unit and no second page width; scale bar and north arrow need a uniform scale.
void validate_page(const page::PageOptions& p, const render::RenderOptions& r) {
  if (p.scale) open_range("--scale", *p.scale, 0, 1e6);
  if (p.scale && p.units == page::Units::None)
    throw OptionError("--scale", "needs --units mm|cm|m: the unit of the model's coordinates");
  if (p.scale && r.page_width_mm)
    throw OptionError("--scale", "conflicts with --page-width-mm: a stated scale sets the page size, give one");
}

/// The page's scale, bar and arrow measure an orthographic view: a perspective has no one scale.
void page_needs_orthographic(const page::PageOptions& p, const view::CameraOptions& c) {
  if (c.projection != view::Projection::Perspective) return;
  const char* flag = p.scale ? "--scale" : p.scale_bar ? "--scale-bar" : p.north_arrow ? "--north-arrow" : nullptr;
  if (flag) throw OptionError(flag, "needs an orthographic view: a perspective has no single scale (drop --perspective)");
}

}  // namespace

double image_bytes(const DrawOptions& o, const view::CameraOptions& camera) {
  const double pixels = static_cast<double>(camera.width) * camera.height;
  double bytes = pixels;  // the A8 raster of a PNG
  const stylize::ShadowMode mode = o.shadow.mode;
  if (o.lines.hatching && (mode == stylize::ShadowMode::Attached || mode == stylize::ShadowMode::Both)) {
    // The attached-shadow grid: per cell a 64-bit z-buffer key, a flag and three floats.
    const double cell = std::max(0.5, static_cast<double>(o.shadow.mask_cell_px));
    bytes += std::ceil(camera.width / cell) * std::ceil(camera.height / cell) * (8 + 1 + 3 * 4);
  }
  return bytes;
}

void validate(const DrawOptions& options, const view::CameraOptions& camera) {
  validate_camera(camera);
  page_needs_orthographic(options.page, camera);
  const double bytes = image_bytes(options, camera);
  if (bytes > kMaxImageBytes)
    throw OptionError("--size", std::to_string(camera.width) + "x" + std::to_string(camera.height) + " needs about " +
                                    number(std::round(bytes / 1e8) / 10) + " GB of image buffers, over the " +
                                    number(kMaxImageBytes / (1ull << 30)) +
                                    " GiB limit (a smaller size, or --shadow paper/none)");
}

void validate(const DrawOptions& options) {
  validate_surface(options.surface);
  validate_features(options.features);
  validate_boundary(options.boundary);
  in_range("--min-points", static_cast<double>(options.min_points), 0, 1e12);
  if (options.max_memory_gb) positive("--max-memory", *options.max_memory_gb, 1e6);
  validate_view(options.view, options.scene);
  validate_thickness(options.thickness);
  validate_finish(options.finish, options.fusion);
  validate_shadow(options.shadow);
  validate_render(options.render);
  validate_plotter(options.plotter);
  validate_page(options.page, options.render);
  validate(options, options.camera);
}

double point_bytes(const differential::SurfaceOptions& surface, std::size_t points) {
  return static_cast<double>(points) *
         (kBytesPerPoint + kBytesPerNeighbour * static_cast<double>(surface.neighbourhood.k));
}

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : kHuge;
}

void validate_memory(double bytes, const std::optional<double>& max_memory_gb, const std::string& what) {
  const double limit = max_memory_gb ? *max_memory_gb * 1e9 : physical_memory_bytes();
  if (bytes <= limit) return;
  const auto gb = [](double b) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g GB", b / 1e9);
    return std::string(text);
  };
  throw OptionError("--max-memory", what + " need about " + gb(bytes) + ", over the " +
                                        (max_memory_gb ? "limit of " + gb(limit) : gb(limit) + " of this machine") +
                                        " (thin the cloud with --voxel or --max-points)");
}

void validate_memory(const DrawOptions& options, std::size_t points, const std::string& source) {
  const view::CameraOptions& c = options.camera;
  validate_memory(image_bytes(options, c) + point_bytes(options.surface, points), options.max_memory_gb,
                  source + ": " + std::to_string(points) + " points (--neighbours " +
                      std::to_string(options.surface.neighbourhood.k) + ") and a " + std::to_string(c.width) + "x" +
                      std::to_string(c.height) + " image");
}

}  // namespace pcsketch
