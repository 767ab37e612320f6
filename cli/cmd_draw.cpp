// pcsketch draw INPUT -o OUT.svg [-o OUT.png] [-o OUT.pdf] [--json OUT.json] [--stages DIR]: the whole pipeline.
// Flags bind straight to the fields of DrawOptions; every default lives in the option structs.

#include <tbb/parallel_for_each.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "views.h"
#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"
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
  ViewRequest views;
  io::ReadOptions read;
  DrawOptions options;
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
  std::printf("%-34s %10.3g  (%s)\n", "noise sigma / h", s.spacing > 0 ? s.input_noise / s.spacing : 0.0,
              s.denoised ? "denoised" : "not denoised");
  std::printf("%-34s %10zu  (%zu points on their own support, the rest share a group's)\n", "curvature fit neighbours",
              s.curvature.fit_neighbours, s.curvature.point_fits);
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

void run_draw(DrawArgs& args, const GlobalOptions& global) {
  if (args.outputs.empty() && args.json.empty() && args.stages.empty())
    throw OptionError("draw", "nothing to write: give -o OUT.svg|png|pdf, --json OUT.json or --stages DIR");
  if (!args.json.empty()) args.outputs.push_back(args.json);
  // Everything that can be refused is refused before the input is read.
  const std::vector<NamedCamera> views = resolve_views(args.options.camera, args.views);
  args.options.camera = views.front().camera;  // the camera options record the first view
  validate(args.options);
  for (const NamedCamera& v : views) validate(args.options, v.camera);
  check_outputs(args, views);

  DrawOptions& options = args.options;
  options.progress = make_progress(global);
  args.read.progress = options.progress;
  Timings timings;
  auto start = Clock::now();
  io::ReadResult read = io::read_point_cloud(args.input, args.read);
  io::check_scale(read.cloud, args.input);
  validate_memory(options, read.cloud.size(), args.input);
  const std::string reduction = describe_reduction(read);
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
  cmd->add_option("INPUT", args->input, "Point cloud: PLY, LAS, XYZ/PTS/TXT/CSV, PCD, OFF or OBJ (mesh vertices)")
      ->required();
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
  cmd->callback([args, &global] { run_draw(*args, global); });
}

void add_draw_options(CLI::App* cmd, DrawOptions& o) {
  add_surface_options(cmd, o.surface);
  add_ridge_valley_options(cmd, o.features);

  // Contours and visibility (paper §IV.B).
  const std::string view_group = "Contours and visibility (paper IV.B)";
  cmd->add_option("--z-max", o.view.contours.z_max_factor,
                  "Paper's z_max: largest distance of the next contour point from the direction line, units of h")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(view_group);
  cmd->add_option("--contour-radius", o.view.contours.radius_factor,
                  "2D neighbourhood radius of the boundary test, units of the projected spacing")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(view_group);
  add_enum(cmd, "--contour-connection", o.view.contours.connection,
           {{"outermost", view::OutlineConnection::Outermost},
            {"direction-guided", view::OutlineConnection::DirectionGuided}},
           "Outline tracing: outermost (no zig-zags) or direction-guided (the paper's)")
      ->group(view_group);
  cmd->add_flag("!--no-interior-contours", o.view.contours.interior,
                "Only the outline: no occluding contours inside it (the paper's contours)")
      ->group(view_group);
  cmd->add_option("--contour-persistence", o.view.contours.persistence_factor,
                  "Interior contours only where n.v reaches this many times the normals' noise on both sides (0: at "
                  "every sign change)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(view_group);
  cmd->add_option("--denoised-contour-length", o.view.contours.denoised_min_length_factor,
                  "On a denoised cloud, interior contours shorter than this many h are left out (noise squiggles)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(view_group);
  cmd->add_flag("!--no-boundary-detection", o.boundary.enabled,
                "No border of open scans: every point may be outline, and hole rims seen through are drawn as "
                "contours")
      ->group(view_group);
  cmd->add_option("--boundary-gap", o.boundary.gap_threshold_deg,
                  "A border point's neighbours leave a gap wider than this in its tangent plane, degrees")
      ->capture_default_str()
      ->group(view_group);
  cmd->add_option("--boundary-min-size", o.boundary.min_size_factor,
                  "Borders spanning less than this, units of h, are small holes: not drawn")
      ->capture_default_str()
      ->group(view_group);
  cmd->add_option("--boundary-radius", o.boundary.tracing.radius_factor,
                  "Tracing radius of boundary lines, units of h")
      ->capture_default_str()
      ->group(view_group);
  cmd->add_flag("!--no-uneven-spacing", o.view.contours.adaptive_spacing,
                "Outline lengths in units of the mean spacing everywhere (the paper's single radius), not of the "
                "local spacing where the cloud is sparser")
      ->group(view_group);
  cmd->add_option("--self-offset", o.view.visibility.self_offset_factor,
                  "Visibility rays start this far from a line vertex, units of h (past its own and its neighbours' "
                  "discs)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(view_group);
  cmd->add_flag("!--no-local-offset", o.view.visibility.offset_from_local_spacing,
                "Self offset in units of h everywhere, not of the source point's disc where the cloud is sparser")
      ->group(view_group);
  cmd->add_flag("!--no-visibility-lift", o.view.visibility.lift_to_source_plane,
                "Cast visibility rays from the line vertices themselves (the paper's), not lifted to the tangent "
                "plane of their source points")
      ->group(view_group);
  add_enum(cmd, "--hidden-lines", o.render.hidden_lines,
           {{"none", render::HiddenLines::None}, {"dashed", render::HiddenLines::Dashed}},
           "Hidden lines: none, or dashed (thin grey, in their own SVG layer)")
      ->group(view_group);

  // Stroke thickness (paper §V).
  const std::string thick = "Stroke thickness (paper V)";
  add_enum(cmd, "--thickness", o.thickness.model,
           {{"constant", stylize::ThicknessModel::Constant},
            {"depth", stylize::ThicknessModel::Depth},
            {"angle", stylize::ThicknessModel::Angle},
            {"combined", stylize::ThicknessModel::Combined}},
           "Width model: constant, depth (nearer thicker), angle (sharper bend thicker) or combined")
      ->group(thick);
  cmd->add_option("--rho-min", o.thickness.rho_min, "Paper's rho_min: thinnest stroke, pixels")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(thick);
  cmd->add_option("--rho-max", o.thickness.rho_max, "Paper's rho_max: thickest stroke, pixels")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(thick);
  cmd->add_option("--cofi", o.thickness.cofi, "Paper's cofi: factor on every width")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(thick);
  cmd->add_flag("!--no-brush", o.thickness.brush, "No brush taper at the ends of lines")->group(thick);

  // Line finish and fusion (paper Fig. 2(d)).
  const std::string finish = "Line finish and fusion (paper Fig. 2(d))";
  cmd->add_flag("!--no-fusion", o.fusion.enabled,
                "Draw every line as traced; by default lines running alongside each other are drawn once (contour "
                "over ridge/valley, outline over interior contour), the other kept in the JSON as fused_into")
      ->group(finish);
  cmd->add_option("--fusion-distance", o.fusion.distance_widths,
                  "Lines closer than this are one, in pen widths (rho-max * cofi)")
      ->capture_default_str()->check(CLI::NonNegativeNumber)->group(finish);
  cmd->add_option("--fusion-min-stretch", o.fusion.min_stretch_px,
                  "Shortest stretch of two lines running together that is drawn once, pixels")
      ->capture_default_str()->check(CLI::NonNegativeNumber)->group(finish);
  cmd->add_flag("!--no-smooth", o.finish.smooth, "Keep the traced vertices; by default lines are smoothed, corners kept")
      ->group(finish);
  cmd->add_option("--min-stroke-length", o.finish.min_length_px, "Lines seen over less than this are left out (a stub continuing a longer line stays), pixels")
      ->capture_default_str()->check(CLI::NonNegativeNumber)->group(finish);

  // Shadow region (paper §VI).
  const std::string shade = "Shadows (paper VI)";
  add_enum(cmd, "--shadow", o.shadow.mode,
           {{"none", stylize::ShadowMode::None}, {"paper", stylize::ShadowMode::Paper},
            {"attached", stylize::ShadowMode::Attached}, {"both", stylize::ShadowMode::Both}},
           "none, paper (hatching between ridge/valley lines and their projection along the light), attached "
           "(hatching of the surface facing away from the light) or both")->group(shade);
  add_vec3(cmd, "--light", "Light travel direction X,Y,Z (default: 45 degrees to xoy, parallel to xoz, Fig. 13; see --light-fixed)",
           [&o](const Vec3d& v) { o.shadow.light.direction = v.cast<float>(); })->group(shade);
  cmd->add_option("--light-elevation", o.shadow.light.elevation_deg, "Light angle to the xoy plane, degrees")
      ->capture_default_str()->group(shade);
  cmd->add_option("--light-azimuth", o.shadow.light.azimuth_deg, "Light rotation around z, degrees (0: xoz plane)")
      ->capture_default_str()->group(shade);
  cmd->add_flag("!--light-fixed", o.shadow.light.follow_camera,
                "Light direction in world axes; by default it is read in the camera's frame and turns with the view "
                "(the same for the paper's +z view)")->group(shade);
  cmd->add_option("--shadow-d", o.shadow.d, "Paper's d (eq. 14): hatch lines at t = k*d along the shadow")
      ->capture_default_str()->check(CLI::PositiveNumber)->group(shade);
  cmd->add_option("--shadow-k", o.shadow.k_set, "Paper's k set (eq. 14), e.g. --shadow-k 0.0625 0.125 0.25 0.5")
      ->capture_default_str()->expected(1, 16)->group(shade);
  cmd->add_option("--hatch-spacing", o.shadow.hatch_spacing_px, "Attached hatching: distance between lines, pixels")
      ->capture_default_str()->check(CLI::PositiveNumber)->group(shade);
  cmd->add_flag("!--no-shade-blocks", o.shadow.shade_blocks, "Paper mode: no grey blocks, hatch strokes only")
      ->group(shade);
  cmd->add_flag("!--shadow-over-background", o.shadow.clip_to_surface,
                "Paper mode: draw the whole region between a line and its projection, also where the background "
                "is seen through it; shading is not cut to the silhouette (default: only over the surface)")
      ->group(shade);

  // What is drawn and how it is written.
  const std::string out = "Output";
  cmd->add_flag("!--no-contours", o.lines.contours, "Leave out contours")->group(out);
  cmd->add_flag("!--no-ridges", o.lines.ridges, "Leave out ridge lines")->group(out);
  cmd->add_flag("!--no-valleys", o.lines.valleys, "Leave out valley lines")->group(out);
  cmd->add_flag("!--no-hatching", o.lines.hatching, "Leave out shadow hatching and shading")->group(out);
  cmd->add_flag("!--no-boundaries", o.lines.boundaries, "Leave out the border lines of open scans")->group(out);
  cmd->add_flag("--plotter", o.render.plotter,
                "Pen-plotter output: centre-lines of one width, no grey fills; strokes merged where their ends meet, "
                "collinear hatching drawn once, dabs left out, each layer sorted to shorten pen-up travel")
      ->group(out);
  CLI::Option* pen_mm = cmd->add_option("--pen-width-mm,--pen-width", o.render.pen_width_mm,
                                        "Plotter line width, page millimetres")
                            ->capture_default_str()
                            ->check(CLI::PositiveNumber)
                            ->group(out);
  cmd->add_option("--pen-width-px", o.render.pen_width,
                  "Plotter line width in image pixels (what --pen-width meant before it took millimetres)")
      ->check(CLI::PositiveNumber)
      ->excludes(pen_mm)
      ->group(out);
  cmd->add_option("--min-stroke-mm", o.plotter.min_stroke_mm,
                  "Plotter: leave out strokes shorter than this after merging, page millimetres (0 keeps all)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(out);
  cmd->add_option("--merge-tolerance-mm", o.plotter.merge_tolerance_mm,
                  "Plotter: join strokes whose ends are this close, page millimetres (0: only ends that coincide)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group(out);
  cmd->add_flag("!--no-plot-sort", o.plotter.sort, "Plotter: keep the drawing order of strokes (no pen-travel sort)")
      ->group(out);
  cmd->add_option_function<double>(
         "--page-width-mm", [&o](const double& w) { o.render.page_width_mm = w; },
         "SVG/PDF page width in millimetres (default: the image size in CSS pixels)")
      ->check(CLI::PositiveNumber)
      ->group(out);
  add_page_options(cmd, o.page);
}

}  // namespace pcsketch::cli
