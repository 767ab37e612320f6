// pcsketch draw INPUT -o OUT.svg [-o OUT.png] [-o OUT.pdf] [--json OUT.json] [--stages DIR]: the whole pipeline.
// Flags bind straight to the fields of DrawOptions; every default lives in the option structs.

#include <tbb/parallel_for_each.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "config.h"
#include "options.h"
#include "views.h"
#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/options_table.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/render/write.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct DrawArgs {
  std::string input;
  std::vector<std::string> outputs;
  std::string json;
  std::string stages;
  bool timings = false;
  std::string config;         ///< --config: options recorded with a drawing, under the flags given
  bool print_config = false;  ///< --print-config: write the resolved options, draw nothing
  ViewRequest views;
  io::ReadOptions read;
  DrawOptions options;
  nlohmann::json read_report;  ///< input_json() of the read, for the JSON output
};

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void print_timings(const Timings& t, const Prepared& prepared, const std::string& reduction) {
  const auto paper = t.table_rows();
  std::printf("%-34s %10s  %s\n", "stage", "seconds", "(paper Table 2 row)");
  for (const auto& stage : t.all_rows()) {
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda.
    const std::string_view name = stage.first;
    const double seconds = stage.second;
    const bool in_paper = std::any_of(paper.begin(), paper.end(), [&](const auto& row) { return row.first == name; });
    std::printf("%-34.*s %10.4f  %s\n", static_cast<int>(name.size()), name.data(), seconds, in_paper ? "*" : "");
  }
  const differential::Surface& s = prepared.surface;
  std::printf("%-34s %10zu\n", "points", prepared.cloud.size());
  if (!reduction.empty()) std::printf("%-34s %s\n", "read: reduced", reduction.c_str());
  std::printf("%-34s %10zu  (%zu isolated, %zu in small clumps)\n", "outliers left out", s.outliers.size(),
              s.isolated_outliers, s.clustered_outliers);
  if (s.scan_lines.found())
    std::printf("%-34s %10zu  (scan lines %g apart, %.0f× their spacing along them)\n", "thinned on scan lines",
                s.thinned.size(), s.scan_lines.spacing, s.scan_lines.anisotropy);
  std::printf("%-34s %10.3g  (%s)\n", "noise sigma / h", s.spacing > 0 ? s.input_noise / s.spacing : 0.0,
              s.denoised ? "denoised" : "not denoised");
  if (s.own_face_lists > 0)
    std::printf("%-34s %10zu  (their neighbours reached the other face)\n", "points on thin parts", s.own_face_lists);
  std::printf("%-34s %10zu  (%zu points fitted one by one at creases, the rest share a group's)\n",
              "curvature fit neighbours", s.curvature.fit_neighbours, s.curvature.point_fits);
}

/// The formats of the stage images: those of the main outputs, PNG when there are none.
std::vector<std::string> stage_extensions(const std::vector<std::string>& outputs) {
  std::vector<std::string> extensions;
  for (const std::string& path : outputs) {
    const std::string ext = fs::path(path).extension().string();
    if (ext != ".json" && std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
      extensions.push_back(ext);
  }
  if (extensions.empty()) extensions.push_back(".png");
  return extensions;
}

/// The --stages directory of one view: DIR itself, or DIR/NAME with several views.
fs::path stage_dir(const std::string& stages, const std::string& view) {
  return view.empty() ? fs::path(stages) : fs::path(stages) / view;
}

/// Every output of every view checked before the input is read: format, directory, no file written twice, --stages
/// never overwriting an -o file.
void check_outputs(const DrawArgs& args, const std::vector<NamedCamera>& views) {
  std::vector<fs::path> keys;
  for (const NamedCamera& v : views)
    for (const std::string& given : args.outputs) {
      const std::string path = view_path(given, v.name);
      try {
        render::check_output(path);
      } catch (const Error& e) {
        throw OptionError(given == args.json ? "--json" : "--output", e.what());
      }
      const fs::path key = same_file_key(path);
      if (std::find(keys.begin(), keys.end(), key) != keys.end())
        throw OptionError("--output", quote(path) + " is written twice");
      keys.push_back(key);
    }
  if (args.stages.empty()) return;
  if (args.views.sheet) throw OptionError("--stages", "conflicts with --sheet: stage images are of one view");
  std::error_code ec;
  const fs::file_status status = fs::status(args.stages, ec);
  if (ec && status.type() != fs::file_type::not_found)
    throw OptionError("--stages", quote(args.stages) + ": " + ec.message());
  fs::path existing = fs::absolute(args.stages);
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  if (!fs::is_directory(existing, ec) || ::access(existing.c_str(), W_OK) != 0)
    throw OptionError("--stages", quote(existing.string()) + " is not a writable directory");
  for (const NamedCamera& v : views)
    for (const std::string_view stem : kStageNames)
      for (const std::string& ext : stage_extensions(args.outputs)) {
        const fs::path stage = stage_dir(args.stages, v.name) / (std::string(stem) + ext);
        if (std::find(keys.begin(), keys.end(), same_file_key(stage.string())) != keys.end())
          throw OptionError("--stages", "would overwrite the output " + quote(stage.string()));
      }
}

/// The outputs and stage images of one view.
void draw_one_view(const DrawArgs& args, const Prepared& prepared, const NamedCamera& v, const GlobalOptions& global,
                   Timings& timings) {
  const DrawOptions& options = args.options;
  if (!args.outputs.empty()) {
    DrawResult result = args.views.sheet ? draw_sheet(prepared, v.camera, *args.views.sheet, options)
                                         : draw_view(prepared, v.camera, options);
    print_warnings(global, result.warnings);
    result.drawing.input = args.read_report;
    const auto start = Clock::now();
    std::vector<fs::path> paths;
    for (const std::string& path : args.outputs) paths.push_back(view_path(path, v.name));
    render::write_drawings(result.drawing, paths, options.render, options.progress);
    result.timings.drawing += seconds_since(start);
    timings += result.timings;
  }
  if (args.stages.empty()) return;
  const fs::path dir = stage_dir(args.stages, v.name);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(FileLoc{dir.string(), {}, {}}, "cannot create the directory: " + ec.message());
  const std::vector<std::string> extensions = stage_extensions(args.outputs);
  // Their warnings are the ones draw_view printed for the same camera.
  const auto stages = stage_drawings(prepared, v.camera, options).stages;
  tbb::parallel_for_each(stages.begin(), stages.end(), [&](const auto& stage) {
    std::vector<fs::path> paths;
    for (const std::string& ext : extensions) paths.push_back(dir / (stage.first + ext));
    render::write_drawings(stage.second, paths, options.render);
  });
}

/// The options as resolved (config, flags, first view's camera) on stdout as JSON, the form --config reads.
void print_config(DrawArgs& args) {
  args.options.camera = resolve_views(args.options.camera, args.views).front().camera;
  validate(args.options);
  std::cout << options::to_json(args.options).dump(2) << "\n";
}

/// The recorded options under the flags given; a recorded sheet is drawn as a sheet again unless flags chose the
/// views. A sheet's views are its own: a recorded direction of sight is then dropped.
void apply_config(DrawArgs& args, const CLI::App& cmd) {
  nlohmann::json config = read_config(args.config);
  const std::optional<page::Arrangement> sheet = take_sheet(config, args.config);
  args.options = with_config(config, args.config, args.options, cmd);
  const bool views_given = !args.views.views.empty() || args.views.turntable || sight_flag_given(cmd);
  if (views_given) return;
  if (!args.views.sheet) args.views.sheet = sheet;
  if (!args.views.sheet) return;
  view::CameraOptions& c = args.options.camera;
  c.named.reset();
  c.direction.reset();
  c.azimuth_deg.reset();
  c.elevation_deg.reset();
}

/// A LAS file is z-up (its format's convention): unless --up or --config set up, it is +z, and with no other view
/// flag the view is the three-quarter one, as for --up alone (along +z, the default sight, a terrain was seen from
/// underneath). A sight given along z keeps up y, since a view along its up is refused.
void apply_conventional_up(DrawArgs& args) {
  if (args.views.up_given || !args.config.empty() || args.input.empty()) return;
  const std::optional<Vec3d> up = io::conventional_up(args.input);
  if (!up) return;
  view::CameraOptions& c = args.options.camera;
  if (c.eye.has_value() != c.target.has_value()) return;  // the sight depends on the cloud's box
  const bool sight_given = c.direction || c.eye;           // else named views and azimuths turn about up
  if (sight_given && !(std::abs(view::sight_frame(c).forward.normalized().dot(*up)) < 0.99)) return;
  c.up = *up;
  args.views.up_given = true;
}

void run_draw(DrawArgs& args, const CLI::App& cmd, const GlobalOptions& global) {
  if (!args.config.empty()) apply_config(args, cmd);
  apply_conventional_up(args);
  if (args.print_config) return print_config(args);
  if (args.input.empty()) throw OptionError("INPUT", "is required (a point cloud to draw)");
  if (args.outputs.empty() && args.json.empty() && args.stages.empty())
    throw OptionError("draw", "nothing to write: give -o OUT.svg|png|pdf, --json OUT.json or --stages DIR");
  if (!args.json.empty()) args.outputs.push_back(args.json);
  // Everything that can be refused is refused before the input is read.
  const std::vector<NamedCamera> views = resolve_views(args.options.camera, args.views);
  args.options.camera = views.front().camera;  // the camera options record the first view
  validate(args.options);
  for (const NamedCamera& v : views) validate(args.options, v.camera);
  check_outputs(args, views);
  for_image(args.read, views.front().camera);
  check_full_resolution(args.read, args.input, point_bytes(args.options.surface, 1));

  DrawOptions& options = args.options;
  options.progress = make_progress(global);
  args.read.progress = options.progress;
  Timings timings;
  auto start = Clock::now();
  io::ReadResult read = io::read_point_cloud(args.input, args.read);
  io::check_scale(read.cloud, args.input);
  validate_memory(options, read.cloud.size(), args.input);
  const std::string reduction = describe_reduction(read);
  args.read_report = input_json(read);
  timings.read = seconds_since(start);
  print_warnings(global, read.warnings);

  const Prepared prepared = prepare(std::move(read.cloud), options);
  print_warnings(global, prepared.warnings);
  timings += prepared.timings;

  // One analysis for every view.
  for (const NamedCamera& v : views) draw_one_view(args, prepared, v, global, timings);
  if (args.timings) print_timings(timings, prepared, reduction);
}

}  // namespace

void add_draw_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<DrawArgs>();
  CLI::App* cmd = app.add_subcommand(
      "draw", "Sketch drawing of a point cloud: contours, ridges, valleys, thickness, shadow hatching (paper Fig. 2)");
  cmd->fallthrough();  // the global flags (-q, --threads) may also follow the subcommand
  cmd->add_option("INPUT", args->input, "Point cloud: PLY, LAS, XYZ/PTS/TXT/CSV, PCD, OFF or OBJ (mesh vertices)");
  cmd->add_option("--config", args->config,
                  "Options recorded with a drawing (its .svg or .json) or written by --print-config; flags given "
                  "here override them");
  cmd->add_flag("--print-config", args->print_config,
                "Write the resolved options as JSON to stdout (the form --config reads) and draw nothing");
  add_read_options(cmd, args->read);
  add_memory_option(cmd, args->options.max_memory_gb);
  cmd->add_option("-o,--output", args->outputs, "Output file; format from the extension: .svg .png .pdf (repeatable)");
  cmd->add_option("--json", args->json, "Write every stroke as JSON (world and image coordinates, widths)");
  cmd->add_option("--stages", args->stages,
                  "Directory for the paper's Fig. 19 columns: b_contours, c_ridges_valleys, d_fused, e_thickness, "
                  "f_shadow (formats of -o, PNG if none)");
  cmd->add_flag("--timings", args->timings, "Print seconds per stage (the paper's Table 2 rows marked *)");
  add_camera_options(cmd, args->options.camera, args->views);
  add_draw_options(cmd, args->options);
  cmd->callback([args, cmd, &global] { run_draw(*args, *cmd, global); });
}

}  // namespace pcsketch::cli
