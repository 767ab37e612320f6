#include "pcsketch/pipeline.h"

#include <tbb/task_group.h>

#include <array>
#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>

#include "core/progress.h"
#include "pcsketch/core/error.h"
#include "pcsketch/options_table.h"
#include "pcsketch/stylize/thickness.h"
#include "pcsketch/validate.h"

namespace pcsketch {

namespace {

using Clock = std::chrono::steady_clock;
using pcsketch::detail::with_progress;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Who is drawn where two lines run together: borders, the outline, interior contours, ridges and valleys.
stylize::FusionRank fusion_rank(const view::ViewResult& view, std::size_t line) {
  if (line < view.outline_count) return stylize::FusionRank::Outline;
  if (line < view.contour_count) return stylize::FusionRank::Interior;
  return view.lines[line].line.kind == LineKind::Boundary ? stylize::FusionRank::Boundary
                                                          : stylize::FusionRank::Feature;
}

/// The view's lines as finished strokes (smoothed, short ones left out, doubles fused), keeping only the kinds
/// `selection` asks for.
std::vector<Stroke> line_strokes(const view::ViewResult& view, const LineSelection& selection,
                                 const stylize::ThicknessOptions& thickness, const DrawOptions& options) {
  std::vector<Polyline> lines;
  std::vector<std::vector<std::uint8_t>> visible;
  std::vector<stylize::FusionRank> line_rank;
  for (std::size_t i = 0; i < view.lines.size(); ++i) {
    const view::ViewLine& v = view.lines[i];
    const LineKind kind = v.line.kind;
    const bool wanted = (kind == LineKind::Contour && selection.contours) ||
                        (kind == LineKind::Ridge && selection.ridges) ||
                        (kind == LineKind::Valley && selection.valleys) ||
                        (kind == LineKind::Boundary && selection.boundaries);
    if (!wanted) continue;
    lines.push_back(stylize::smooth_line(v.line, view.camera, options.finish));
    visible.push_back(v.visible);
    line_rank.push_back(fusion_rank(view, i));
  }
  stylize::StrokesResult strokes = stylize::make_strokes(lines, view.camera, visible, thickness);
  stylize::drop_short_strokes(strokes, options.finish);
  std::vector<stylize::FusionRank> rank;
  for (const std::uint32_t line : strokes.line) rank.push_back(line_rank[line]);
  return stylize::fuse_strokes(std::move(strokes.strokes), rank, options.thickness.rho_max * options.thickness.cofi,
                               options.fusion)
      .strokes;
}

/// An empty drawing of the right size and camera (a cloud that could not be analysed).
Drawing empty_drawing(const view::Camera& camera, const Vec3d& origin, const nlohmann::json& parameters) {
  Drawing d;
  d.width = camera.width;
  d.height = camera.height;
  d.origin = origin;
  d.camera = camera.to_json();
  d.parameters = parameters;
  return d;
}

/// The recorded parameters: every option plus the values the relative defaults resolved to on this cloud.
nlohmann::json parameters_json(const Prepared& prepared, const DrawOptions& options,
                               const view::CameraOptions& camera) {
  DrawOptions drawn = options;
  drawn.camera = camera;
  nlohmann::json j = options::to_json(drawn);
  j["resolved"] = {{"points", prepared.cloud.size()},
                   {"spacing_h", prepared.surface.spacing},
                   {"outliers_removed", prepared.surface.outliers.size()},
                   {"isolated_outliers", prepared.surface.isolated_outliers},
                   {"clustered_outliers", prepared.surface.clustered_outliers},
                   {"scan_line_spacing", prepared.surface.scan_lines.spacing},
                   {"scan_line_thinned", prepared.surface.thinned.size()},
                   {"input_noise_sigma", prepared.surface.input_noise},
                   {"denoised", prepared.surface.denoised},
                   {"normal_noise", prepared.surface.normal_noise},
                   {"thin_part_points", prepared.surface.own_face_lists},
                   {"border_points", prepared.boundary.border_points},
                   {"small_holes", prepared.boundary.small_holes},
                   {"tracing_radius_r", prepared.features.radius},
                   {"ridge_threshold", prepared.features.detection.ridge_threshold},
                   {"valley_threshold", prepared.features.detection.valley_threshold}};
  return j;
}

struct StyleRequest {
  LineSelection lines;
  stylize::ThicknessOptions thickness;
};

/// Shadow hatching of the view's visible ridge and valley lines (as selected), appended to the drawing; its warnings
/// are appended to `warnings`.
void add_shadows(const Prepared& prepared, const view::ViewResult& view, const LineSelection& selection,
                 const stylize::ShadowOptions& options, Drawing& drawing, Warnings& warnings) {
  std::vector<Polyline> lines;
  std::vector<std::vector<std::uint8_t>> visible;
  for (const view::ViewLine& v : view.lines) {
    if ((v.line.kind == LineKind::Ridge && selection.ridges) || (v.line.kind == LineKind::Valley && selection.valleys)) {
      lines.push_back(v.line);
      visible.push_back(v.visible);
    }
  }
  const stylize::ShadowInput input{prepared.cloud.positions, prepared.cloud.normals, prepared.local_spacing,
                                   *prepared.scene, view.camera, prepared.surface.spacing, lines, visible};
  stylize::ShadowResult shadows = stylize::shadow_hatching(input, options);
  drawing.strokes.insert(drawing.strokes.end(), std::make_move_iterator(shadows.strokes.begin()),
                         std::make_move_iterator(shadows.strokes.end()));
  drawing.regions = std::move(shadows.regions);
  warnings.insert(warnings.end(), shadows.warnings.begin(), shadows.warnings.end());
}

/// Lines with thickness, then (when selected) shadow hatching; adds the seconds spent to `timings` and the shadow
/// step's warnings to `warnings`.
Drawing style(const Prepared& prepared, const view::ViewResult& view, const StyleRequest& request,
              const DrawOptions& options, const nlohmann::json& parameters, Timings& timings, Warnings& warnings) {
  auto start = Clock::now();
  Drawing d = empty_drawing(view.camera, prepared.cloud.origin, parameters);
  d.strokes = line_strokes(view, request.lines, request.thickness, options);
  timings.drawing += seconds_since(start);
  if (request.lines.hatching && options.shadow.mode != stylize::ShadowMode::None) {
    start = Clock::now();
    add_shadows(prepared, view, request.lines, with_progress(options.shadow, options.progress), d, warnings);
    timings.shadows += seconds_since(start);
  }
  return d;
}

/// With render.plotter, the drawing becomes plotter paths (plotter/plot_order.h); the pen travel before and after
/// is recorded in Drawing::plotter.
void plotter_paths(Drawing& drawing, const DrawOptions& options, Timings& timings) {
  if (!options.render.plotter) return;
  const auto start = Clock::now();
  const bool hidden = options.render.hidden_lines == render::HiddenLines::Dashed;
  plotter::PlotterResult plotted = plotter::plot_order(
      drawing, render::mm_per_pixel(drawing, options.render), options.plotter, hidden);
  drawing = std::move(plotted.drawing);
  drawing.plotter = {{"before_ordering", plotted.before.to_json()},
                     {"after_ordering", plotted.after.to_json()},
                     {"joins", plotted.joins},
                     {"duplicate_hatching_mm", plotted.duplicate_hatching_mm},
                     {"short_strokes_dropped", plotted.short_strokes_dropped}};
  timings.drawing += seconds_since(start);
}

/// The page (scale, scale bar, north arrow) of a drawing at `pixels_per_unit`, then with render.plotter its plotter
/// paths.
void finish_page(Drawing& drawing, double pixels_per_unit, const std::optional<Vec2f>& north,
                 const DrawOptions& options, Timings& timings, Warnings& warnings) {
  const Warnings page_warnings = page::annotate(drawing, pixels_per_unit, north, options.page);
  warnings.insert(warnings.end(), page_warnings.begin(), page_warnings.end());
  plotter_paths(drawing, options, timings);
}

view::ViewResult compute_view(const Prepared& prepared, const view::Camera& camera, const DrawOptions& options,
                              Timings& timings, Warnings& warnings) {
  std::vector<Polyline> lines = prepared.features.lines;
  lines.insert(lines.end(), prepared.boundary.lines.begin(), prepared.boundary.lines.end());
  // Without border lines the outline may not run along a border either: it would draw the border as a contour.
  std::vector<std::uint8_t> undrawn;
  if (!options.lines.boundaries)
    for (const std::uint8_t rim : prepared.boundary.border)
      undrawn.push_back(rim == features::Boundary::kDrawnRim ? features::Boundary::kUndrawnRim : rim);
  view::ViewResult v = view::compute_view(prepared.cloud, prepared.surface, *prepared.scene, lines, camera,
                                          with_progress(options.view, options.progress),
                                          options.lines.boundaries ? prepared.boundary.border : undrawn);
  timings.contour_points += v.timings.contour_points;
  timings.contour_connection += v.timings.contour_connection;
  timings.visibility += v.timings.visibility;
  warnings.insert(warnings.end(), v.warnings.begin(), v.warnings.end());
  return v;
}

/// `options` with the progress it resolves to (its own, else `progress`) called under `mutex`, so that stages
/// running at once may share a callback.
template <class Options>
Options serialised(Options options, const ProgressFn& progress, std::mutex& mutex) {
  options = with_progress(std::move(options), progress);
  if (options.progress)
    options.progress = [report = std::move(options.progress), &mutex](std::string_view stage, double fraction) {
      const std::lock_guard lock(mutex);
      return report(stage, fraction);
    };
  return options;
}

/// The ridge and valley lines, then the borders, into `p` (their rows of p.timings, their warnings); progress is
/// reported under `reporting`.
void lines_and_borders(Prepared& p, const neighbourhood::KdTree* tree, const DrawOptions& options,
                       std::mutex& reporting) {
  p.features = features::extract_ridge_valley_lines(
      p.cloud, p.surface, serialised(options.features, options.progress, reporting));
  // Only the lines read the per-point curvature: 32 B a point freed before the scene and the views (the peak).
  for (std::vector<float>* v : {&p.surface.curvature.k1, &p.surface.curvature.k2}) *v = std::vector<float>();
  for (std::vector<Vec3f>* v : {&p.surface.curvature.dir1, &p.surface.curvature.dir2}) *v = std::vector<Vec3f>();
  p.timings.ridge_valley_points = p.features.timings.detection;
  p.timings.ridge_valley_connection = p.features.timings.tracing + p.features.timings.joining;
  p.warnings.insert(p.warnings.end(), p.features.warnings.begin(), p.features.warnings.end());

  const auto start = Clock::now();
  p.boundary = features::find_boundaries(p.cloud.positions, p.cloud.normals, p.surface.neighbourhoods,
                                         p.surface.spacing, serialised(options.boundary, options.progress, reporting),
                                         tree);
  p.timings.boundary = seconds_since(start);
}

}  // namespace

nlohmann::json DrawOptions::to_json() const { return options::to_json(*this); }

Prepared prepare(PointCloud cloud, const DrawOptions& options) {
  validate(options);
  validate_memory(options, cloud.size(), "the cloud");
  Prepared p;
  p.cloud = std::move(cloud);
  if (p.cloud.size() < std::max<std::size_t>(options.min_points, 3)) {
    p.warnings.push_back("the cloud has " + std::to_string(p.cloud.size()) +
                         " points, too few to analyse: the drawing is empty");
    return p;
  }
  // The analysis's kd-tree and its grid, reused by the border search (a tree's build is serial: 4% of a 1M draw).
  std::optional<neighbourhood::KdTree> tree;
  try {
    p.surface = differential::analyse_surface(p.cloud, with_progress(options.surface, options.progress), &tree);
  } catch (const Error& e) {
    // analyse_surface rejects clouds without 3 distinct points: nothing to draw, but not an error of the input.
    p.warnings.push_back(std::string("cannot analyse the cloud (") + e.what() + "): the drawing is empty");
    return p;
  }
  const differential::SurfaceTimings& st = p.surface.timings;
  p.timings.reorder = st.reorder;
  p.timings.neighbourhoods = st.neighbourhoods;
  p.timings.scan_lines = st.scan_lines;
  p.timings.outliers = st.outliers;
  p.timings.denoise = st.denoise;
  p.timings.normals = st.normals + st.orientation;
  p.timings.curvature = st.curvature;
  p.warnings.insert(p.warnings.end(), p.surface.warnings.begin(), p.surface.warnings.end());

  // The scene reads only positions, normals and spacing: it is built beside the lines and the borders, so that the
  // serial parts of Embree's build and theirs each leave the other's core busy. One callback at a time.
  std::mutex reporting;
  tbb::task_group beside;
  beside.run([&] {
    p.local_spacing = view::local_spacing(p.surface.neighbourhoods);
    p.scene.emplace(p.cloud.positions, p.cloud.normals, p.local_spacing,
                    serialised(options.scene, options.progress, reporting));
  });
  try {
    lines_and_borders(p, tree ? &*tree : nullptr, options, reporting);
  } catch (...) {
    beside.wait();  // the task writes to `p`
    throw;
  }
  // The scene's row is the wait it adds: its time beside the lines and borders is in their rows.
  const auto start = Clock::now();
  beside.wait();
  p.timings.scene = seconds_since(start);
  return p;
}

namespace {

/// The drawing of one view with `camera` (made from `camera_options`, both validated by the caller), before its page
/// and plotter paths.
DrawResult draw_unfinished(const Prepared& prepared, const view::Camera& camera,
                           const view::CameraOptions& camera_options, const DrawOptions& options) {
  DrawResult result;
  const nlohmann::json parameters = parameters_json(prepared, options, camera_options);
  if (!prepared.analysed()) {
    result.drawing = empty_drawing(camera, prepared.cloud.origin, parameters);
    return result;
  }
  const view::ViewResult v = compute_view(prepared, camera, options, result.timings, result.warnings);
  result.drawing =
      style(prepared, v, {options.lines, options.thickness}, options, parameters, result.timings, result.warnings);
  return result;
}

}  // namespace

DrawResult draw_view(const Prepared& prepared, const view::CameraOptions& camera_options,
                     const DrawOptions& options) {
  validate(options, camera_options);
  const view::Camera camera = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, camera_options);
  DrawResult result = draw_unfinished(prepared, camera, camera_options, options);
  if (prepared.analysed())
    finish_page(result.drawing, camera.scale, page::north_in_image(camera), options, result.timings, result.warnings);
  return result;
}

DrawResult draw_sheet(const Prepared& prepared, const view::CameraOptions& camera_options,
                      page::Arrangement arrangement, const DrawOptions& options) {
  // Each view unfinished (no page, no plotter paths): the sheet is finished as one page.
  DrawResult result;
  std::vector<page::SheetView> views;
  for (const view::NamedView name : page::sheet_views(arrangement)) {
    view::CameraOptions camera_view = camera_options;
    camera_view.projection = view::Projection::Orthographic;
    camera_view.direction.reset();
    camera_view.azimuth_deg.reset();
    camera_view.elevation_deg.reset();
    camera_view.named = name;
    validate(options, camera_view);
    const view::Camera camera = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, camera_view);
    DrawResult drawn = draw_unfinished(prepared, camera, camera_view, options);
    result.timings += drawn.timings;
    result.warnings.insert(result.warnings.end(), drawn.warnings.begin(), drawn.warnings.end());
    views.push_back({name, std::move(drawn.drawing), camera});
  }
  auto [sheet, scale] = page::compose_sheet(std::move(views), arrangement);
  result.drawing = std::move(sheet);
  DrawOptions sheet_options = options;
  if (options.page.north_arrow) {
    result.warnings.push_back("--north-arrow: not drawn on a sheet, whose views look different ways");
    sheet_options.page.north_arrow = false;
  }
  finish_page(result.drawing, scale, std::nullopt, sheet_options, result.timings, result.warnings);
  return result;
}

DrawResult draw(PointCloud cloud, const DrawOptions& options) {
  const Prepared prepared = prepare(std::move(cloud), options);
  DrawResult result = draw_view(prepared, options.camera, options);
  result.timings += prepared.timings;
  result.warnings.insert(result.warnings.begin(), prepared.warnings.begin(), prepared.warnings.end());
  return result;
}

StageDrawings stage_drawings(const Prepared& prepared, const view::CameraOptions& camera_options,
                             const DrawOptions& options) {
  validate(options, camera_options);
  const view::Camera camera = view::make_camera(prepared.cloud.positions, prepared.cloud.origin, camera_options);
  const nlohmann::json parameters = parameters_json(prepared, options, camera_options);
  stylize::ThicknessOptions constant = options.thickness;
  constant.model = stylize::ThicknessModel::Constant;
  constant.brush = false;
  const std::vector<std::pair<std::string, StyleRequest>> columns = {
      {std::string(kStageNames[0]),
       {{.contours = true, .ridges = false, .valleys = false, .hatching = false}, constant}},
      {std::string(kStageNames[1]),
       {{.contours = false, .ridges = true, .valleys = true, .hatching = false, .boundaries = false}, constant}},
      {std::string(kStageNames[2]), {{.contours = true, .ridges = true, .valleys = true, .hatching = false}, constant}},
      {std::string(kStageNames[3]),
       {{.contours = true, .ridges = true, .valleys = true, .hatching = false}, options.thickness}},
      {std::string(kStageNames[4]),
       {{.contours = true, .ridges = true, .valleys = true, .hatching = true}, options.thickness}}};
  StageDrawings out;
  if (!prepared.analysed()) {
    for (const auto& column : columns)
      out.stages.emplace_back(column.first, empty_drawing(camera, prepared.cloud.origin, parameters));
    return out;
  }
  const view::ViewResult v = compute_view(prepared, camera, options, out.timings, out.warnings);
  // The five styles share one view; shading runs once per style but reports the same warnings each time.
  Warnings style_warnings;
  for (const auto& [stem, request] : columns) {
    style_warnings.clear();
    out.stages.emplace_back(stem, style(prepared, v, request, options, parameters, out.timings, style_warnings));
    finish_page(out.stages.back().second, camera.scale, page::north_in_image(camera), options, out.timings,
                style_warnings);
  }
  out.warnings.insert(out.warnings.end(), style_warnings.begin(), style_warnings.end());
  return out;
}

}  // namespace pcsketch
