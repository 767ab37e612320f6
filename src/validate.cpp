#include "pcsketch/validate.h"

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "pcsketch/options_table.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/view/camera.h"

namespace pcsketch {

namespace {

constexpr double kHuge = std::numeric_limits<double>::max();

/// Every option under `prefix` ("camera." or "" for all) within the range of its table entry.
void check_ranges(const DrawOptions& o, const std::string& prefix) {
  for (const options::Option& option : options::table())
    if (option.key.starts_with(prefix)) options::check(option, option.get(o));
}

/// A direction: non-zero (any length; the camera scales it before normalising). Finite: the table's check.
void direction(const std::string& flag, const Vec3d& v) {
  if (v.cwiseAbs().maxCoeff() == 0) throw OptionError(flag, "must be a non-zero vector");
}

std::string vec_text(const Vec3d& v) { return number(v.x()) + "," + number(v.y()) + "," + number(v.z()); }

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

/// What the ranges of the table cannot say about the camera: directions, and one sight with an up across it.
void validate_camera(const view::CameraOptions& c) {
  if (c.direction) direction("--view", *c.direction);
  direction("--up", c.up);
  if (c.eye && c.target && *c.eye == *c.target) throw OptionError("--eye", "must differ from --target");
  one_sight(c);
  sight_not_along_up(c);
}

/// What the ranges of the table cannot say about the other options: relations between them, lists, parity.
void validate_relations(const DrawOptions& o) {
  if (o.view.visibility.smoothing_window % 2 == 0)
    throw OptionError("view.visibility.smoothing_window", "must be odd");
  const stylize::ThicknessOptions& t = o.thickness;
  if (t.rho_min > t.rho_max) throw OptionError("--rho-min", "must not exceed --rho-max (" + number(t.rho_max) + ")");
  if (t.depth_range && !(std::isfinite(t.depth_range->near) && std::isfinite(t.depth_range->far)))
    throw OptionError("thickness.depth_range", "must be two finite numbers");
  if (o.shadow.light.direction) direction("--light", o.shadow.light.direction->cast<double>());
  if (o.shadow.k_set.empty()) throw OptionError("--shadow-k", "needs at least one value");
}

/// A stated scale (its range is the table's) needs the model's unit and no second page width.
void validate_page(const page::PageOptions& p, const render::RenderOptions& r) {
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
  DrawOptions seen = options;  // the table reads options: this camera in place of options.camera
  seen.camera = camera;
  check_ranges(seen, "camera.");
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
  check_ranges(options, "");
  validate_relations(options);
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
