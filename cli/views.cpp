#include "views.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "pcsketch/core/error.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {

namespace {

/// The named views, in view::NamedView order.
std::vector<std::string> view_names() {
  std::vector<std::string> names;
  for (int v = 0; v <= static_cast<int>(view::NamedView::Iso); ++v)
    names.emplace_back(view::to_string(static_cast<view::NamedView>(v)));
  return names;
}

/// "front, back, …" for messages and help.
std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

/// Flags that choose the direction of sight, as the user spelled them; --elevation alone may tilt a turntable.
std::vector<std::string> sight_flags(const view::CameraOptions& c) {
  std::vector<std::string> flags;
  if (c.direction || c.named) flags.emplace_back("--view");
  if (c.azimuth_deg) flags.emplace_back("--azimuth");
  if (c.elevation_deg) flags.emplace_back("--elevation");
  if (c.eye && c.target) flags.emplace_back("--eye/--target");
  return flags;
}

}  // namespace

Vec3d parse_vec3(const std::string& flag, const std::string& text) {
  std::istringstream in(text);
  Vec3d v;
  char c1 = 0, c2 = 0;
  if (!(in >> v.x() >> c1 >> v.y() >> c2 >> v.z()) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
      !v.allFinite())
    throw CLI::ValidationError(flag, "expected three numbers X,Y,Z, got " + quote(text));
  return v;
}

void add_camera_options(CLI::App* cmd, view::CameraOptions& c, ViewRequest& request) {
  const std::string group = "Camera";
  const std::string names = listed(view_names());
  cmd->add_option_function<std::string>(
         "--view",
         [&c, names](const std::string& s) {
           if (const auto named = view::parse_named_view(s)) {
             c.named = named;
             return;
           }
           if (s.find(',') == std::string::npos)
             throw CLI::ValidationError("--view",
                                        "expected a view name (" + names + ") or three numbers X,Y,Z, got " + quote(s));
           c.direction = parse_vec3("--view", s);
         },
         "View: a name relative to --up (" + names +
             ") or the direction of sight X,Y,Z (default 0,0,1: the paper looks along +z)")
      ->group(group);
  add_vec3(cmd, "--up",
           "Up hint X,Y,Z (default 0,1,0, and 0,0,1 for LAS files); alone, without a view, gives the three-quarter "
           "view",
           [&c, &request](const Vec3d& v) {
             c.up = v;
             request.up_given = true;
           })
      ->group(group);
  cmd->add_option_function<double>(
         "--azimuth", [&c](const double& a) { c.azimuth_deg = a; },
         "Viewer azimuth around up, degrees (0 = the front view; positive turns toward the left view)")
      ->group(group);
  cmd->add_option_function<double>(
         "--elevation", [&c](const double& e) { c.elevation_deg = e; },
         "Viewer elevation above the horizon, degrees (positive looks down)")
      ->group(group);
  cmd->add_option("--views", request.views,
                  "Several named views from one analysis, e.g. front,top,iso: one file per view, out.svg -> "
                  "out-front.svg, …")
      ->delimiter(',')
      ->check(CLI::IsMember(view_names()))
      ->group(group);
  cmd->add_option("--turntable", request.turntable,
                  "N views around up, 360/N degrees apart, from one analysis, at --elevation (default 15): "
                  "out.svg -> out-az000.svg, out-az030.svg, …")
      ->check(CLI::Range(1, 360))
      ->group(group);
  cmd->add_option_function<std::string>(
         "--sheet", [&request](const std::string& s) { request.sheet = page::parse_arrangement(s); },
         "Front, top, side and iso views on one page, the first three at one scale and aligned: first (ISO: top "
         "view below the front, left view on its right) or third angle (ASME: top view above, right view right)")
      ->check(CLI::IsMember({"first", "third"}))
      ->group(group);
  cmd->add_flag_function(
         "--perspective", [&c](std::int64_t) { c.projection = view::Projection::Perspective; },
         "Perspective projection (default orthographic)")
      ->group(group);
  add_vec3(cmd, "--eye", "Perspective eye point X,Y,Z (world)", [&c](const Vec3d& v) { c.eye = v; })->group(group);
  add_vec3(cmd, "--target", "Perspective target point X,Y,Z (world)", [&c](const Vec3d& v) {
    c.target = v;
  })->group(group);
  cmd->add_option_function<std::string>(
         "--size",
         [&c](const std::string& s) {
           int w = 0, h = 0;
           char x = 0;
           std::istringstream in(s);
           if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || w <= 0 || h <= 0 || !(in >> std::ws).eof())
             throw CLI::ValidationError("--size", "expected WxH in pixels, e.g. 1024x768, got " + quote(s));
           c.width = w;
           c.height = h;
         },
         "Image size WxH in pixels (default 1024x1024)")
      ->group(group);
}

std::vector<NamedCamera> resolve_views(const view::CameraOptions& camera, const ViewRequest& request) {
  const std::vector<std::string> flags = sight_flags(camera);
  if (request.sheet) {
    std::string other = !flags.empty() ? flags[0] : !request.views.empty() ? "--views" : "";
    if (request.turntable) other = "--turntable";
    if (camera.projection == view::Projection::Perspective) other = "--perspective";
    if (!other.empty())
      throw OptionError("--sheet", "conflicts with " + other + ": the sheet's views are its own, orthographic");
    view::CameraOptions front = camera;  // what the sheet's first view is, so that it is validated as drawn
    front.named = view::NamedView::Front;
    return {{"", front}};
  }
  if (!request.views.empty() && request.turntable)
    throw OptionError("--views", "conflicts with --turntable: give one list of views");
  if (!request.views.empty() && !flags.empty())
    throw OptionError("--views", "conflicts with " + flags[0] + ": --views sets the direction of every view");
  if (request.turntable && !flags.empty() && flags != std::vector<std::string>{"--elevation"})
    throw OptionError("--turntable", "conflicts with " + flags[0] + ": --turntable sets the azimuth of every view");

  std::vector<NamedCamera> out;
  for (const std::string& name : request.views) {
    view::CameraOptions c = camera;
    c.named = view::parse_named_view(name);
    out.push_back({name, c});
  }
  if (request.turntable) {
    const int n = *request.turntable;
    for (int k = 0; k < n; ++k) {
      view::CameraOptions c = camera;
      c.azimuth_deg = 360.0 * k / n;
      c.elevation_deg = camera.elevation_deg.value_or(view::kThreeQuarterElevationDeg);
      // Whole degrees, three digits: distinct for N ≤ 360 (steps of at least 1°), and sorted as the turn goes.
      char name[16];
      std::snprintf(name, sizeof name, "az%03ld", std::lround(*c.azimuth_deg));
      out.push_back({name, c});
    }
  }
  if (!out.empty()) return out;
  view::CameraOptions single = camera;
  if (request.up_given && flags.empty()) {
    // A z-up scan seen along +z would be seen from underneath: --up alone means "show it upright".
    single.azimuth_deg = view::kThreeQuarterAzimuthDeg;
    single.elevation_deg = view::kThreeQuarterElevationDeg;
  }
  return {{"", single}};
}

std::string view_path(const std::string& path, const std::string& name) {
  if (name.empty()) return path;
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + "-" + name + p.extension().string())).string();
}

}  // namespace pcsketch::cli
