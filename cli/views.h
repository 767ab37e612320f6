#pragma once
// The camera flags of `draw`: one view (--view, --azimuth, --eye, …) or several from one analysis (--views,
// --turntable), each with the file-name suffix its outputs get.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/page/page.h"
#include "pcsketch/view/camera.h"

namespace pcsketch::cli {

/// "X,Y,Z" → vector; throws CLI::ValidationError (exit 1) naming `flag` otherwise.
Vec3d parse_vec3(const std::string& flag, const std::string& text);

/// A vector-valued flag "X,Y,Z" that stores into `target` when given.
template <class Set>
CLI::Option* add_vec3(CLI::App* cmd, const std::string& name, const std::string& help, Set set) {
  const std::string flag = name.substr(name.rfind(',') + 1);
  return cmd->add_option_function<std::string>(
      name, [flag, set](const std::string& s) { set(parse_vec3(flag, s)); }, help);
}

/// Views asked for beyond the single camera of CameraOptions.
struct ViewRequest {
  std::vector<std::string> views;  ///< --views front,top,…: named views
  std::optional<int> turntable;    ///< --turntable N: N azimuths, 360/N degrees apart
  bool up_given = false;           ///< --up was given (alone it means the three-quarter view)
  std::optional<page::Arrangement> sheet;  ///< --sheet first|third: front, top, side and iso on one page
};

/// One view to draw and the suffix of its files ("" for a single view: the files are named as given).
struct NamedCamera {
  std::string name;
  view::CameraOptions camera;
};

/// The camera flags the option table cannot bind (--view, --up, --azimuth, --elevation, --perspective, --eye,
/// --target, --size, --views, --turntable) bound to `camera` and `request`, which must outlive the parse; --fov and
/// --margin come with add_draw_options.
void add_camera_options(CLI::App* cmd, view::CameraOptions& camera, ViewRequest& request);

/// The views to draw, in order (one for --sheet: its camera gives up, size and margin). `--up` with no view flag is the three-quarter view; `--views` and `--turntable`
/// give one camera per view (turntable azimuths named az000, az030, …, at --elevation or 15°).
/// @throws OptionError (exit 1) for view flags that conflict (--sheet sets every direction itself).
std::vector<NamedCamera> resolve_views(const view::CameraOptions& camera, const ViewRequest& request);

/// `path` with "-name" before its extension (out.svg → out-front.svg); `path` itself when `name` is empty.
std::string view_path(const std::string& path, const std::string& name);

}  // namespace pcsketch::cli
