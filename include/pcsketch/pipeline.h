#pragma once
// The whole pipeline: a raw point cloud in, a Drawing of one view out (paper Fig. 2). Split in two so that a second
// view of the same cloud reuses every view-independent result: prepare() once, draw_view() per view.

#include <array>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/differential/surface.h"
#include "pcsketch/features/boundary_lines.h"
#include "pcsketch/features/ridge_valley_lines.h"
#include "pcsketch/page/page.h"
#include "pcsketch/plotter/plot_order.h"
#include "pcsketch/render/options.h"
#include "pcsketch/stylize/fuse.h"
#include "pcsketch/stylize/line_finish.h"
#include "pcsketch/stylize/shadow.h"
#include "pcsketch/stylize/thickness.h"
#include "pcsketch/view/camera.h"
#include "pcsketch/view/surface_scene.h"
#include "pcsketch/view/view.h"

namespace pcsketch {

/// Which lines a drawing shows (the columns of the paper's Fig. 19 switch them on one by one).
struct LineSelection {
  bool contours = true;  ///< outline and interior occluding contours
  bool ridges = true;
  bool valleys = true;
  bool hatching = true;  ///< shadow hatching and shade regions (paper §VI)
  bool boundaries = true;  ///< the border of an open scan (kind Boundary; closed clouds have none)
};

/// Every option of every stage, so that one struct (and the CLI flags bound to its fields) reproduces a drawing.
/// Defaults are relative to the cloud (lengths in units of the mean spacing h, widths in output pixels).
struct DrawOptions {
  differential::SurfaceOptions surface;        ///< neighbourhoods, normals, curvature (view-independent)
  features::RidgeValleyOptions features;       ///< ridge/valley detection (α), tracing (r), joining (β)
  features::BoundaryOptions boundary;          ///< the border of open scans, small holes left out
  view::SurfaceSceneOptions scene;             ///< the cloud as oriented discs for ray casting
  view::CameraOptions camera;                  ///< default: the paper's orthographic view along +z, 1024 × 1024 px
  view::ViewOptions view;                      ///< contours (z_max, …) and visibility
  stylize::FinishOptions finish;               ///< smoothing that keeps corners, short strokes left out
  stylize::ThicknessOptions thickness;         ///< ρ_min, ρ_max, cofi, depth/angle/brush models
  stylize::FusionOptions fusion;               ///< doubled lines drawn once (paper Fig. 2(d))
  /// Light, d, k set, attached hatching (paper §VI). The light turns with the camera here (stylize's own default
  /// keeps it fixed in world axes): for the paper's +z view both are the paper's Fig. 13 light; for any other view a
  /// world-fixed light often comes from behind and hatches nearly everything.
  stylize::ShadowOptions shadow{.light = {.follow_camera = true}};
  render::RenderOptions render;                ///< hidden lines, plotter mode, page size (used by the writers)
  plotter::PlotterOptions plotter;             ///< with render.plotter: merging, sorting, dabs left out (page mm)
  page::PageOptions page;                      ///< stated scale (1:20), scale bar, north arrow
  LineSelection lines;                         ///< which kinds of line are drawn
  /// Clouds with fewer points than this give an empty drawing and a warning instead of an analysis: a surface
  /// needs a neighbourhood (k) per point. 3 is the least a plane needs; smaller clouds cannot be drawn.
  std::size_t min_points = 3;
  /// Most memory a drawing may need, GB (1e9 bytes), estimated from the image and the point count before the analysis
  /// (validate_memory in validate.h); unset: the machine's physical memory.
  std::optional<double> max_memory_gb;
  ProgressFn progress;  ///< optional: stage name and fraction; false cancels (pcsketch::Cancelled)

  /// Every option, for Drawing::parameters: options::to_json (options_table.h), keyed by member path;
  /// options::from_json reads it back.
  nlohmann::json to_json() const;
};

/// Seconds per stage. The paper's Table 2 rows are listed by table_rows(); the other fields are our finer split.
struct Timings {
  double read = 0;                    ///< reading the file (filled by the caller that read it)
  double reorder = 0;                 ///< spatial reordering
  double neighbourhoods = 0;          ///< kd-tree and k-NN lists
  double scan_lines = 0;              ///< finding scan lines and thinning them (clean::find_scan_lines)
  double outliers = 0;                ///< finding outliers and leaving them out of the cloud
  double denoise = 0;                 ///< noise estimate and, on noisy clouds, feature-preserving denoising
  double normals = 0;                 ///< PCA normals and orientation
  double curvature = 0;               ///< quadric fit
  double ridge_valley_points = 0;     ///< Table 2 "ridge-valley points extraction" (detection)
  double ridge_valley_connection = 0; ///< Table 2 "ridge-valley points connection" (tracing + joining)
  double boundary = 0;                ///< border points of open scans, traced into lines
  double scene = 0;                   ///< building the oriented-disc scene: the wait it adds beside the lines
  double contour_points = 0;          ///< Table 2 "contour points extraction"
  double contour_connection = 0;      ///< Table 2 "contour line connection"
  double visibility = 0;              ///< ray casting of every line
  double shadows = 0;                 ///< shadow regions and hatching
  double drawing = 0;                 ///< Table 2 "drawing": stroke thickness and writing the outputs
  double total() const;

  /// The paper's Table 2 rows, in its order, then "total": (name, seconds).
  std::vector<std::pair<std::string_view, double>> table_rows() const;
  /// Every row in pipeline order (the Table 2 rows under the paper's names among ours), then "total".
  std::vector<std::pair<std::string_view, double>> all_rows() const;
  Timings& operator+=(const Timings& other);
};

/// Everything view-independent, computed once per cloud.
struct Prepared {
  PointCloud cloud;                      ///< reordered, with oriented normals
  /// Neighbourhoods, spacing h, curvature: its per-point arrays (k1, k2, dir1, dir2) are emptied once the lines are
  /// extracted, 32 B a point the views do not need (call differential::analyse_surface to keep them).
  differential::Surface surface;
  features::RidgeValleyLines features;   ///< ridge and valley lines
  features::Boundary boundary;           ///< border points and lines (open scans)
  std::vector<float> local_spacing;      ///< #P disc radii of the scene before its factor (view::local_spacing)
  std::optional<view::SurfaceScene> scene;  ///< absent when the cloud was too small to analyse
  Timings timings;
  Warnings warnings;
  bool analysed() const { return scene.has_value(); }
};

/// Analyses `cloud` (neighbourhoods, normals, curvature), extracts ridge and valley lines and builds the ray-casting
/// scene. A cloud too small or too degenerate to analyse (fewer than `min_points`, fewer than 3 distinct points)
/// gives a Prepared without analysis and a warning: draw_view then returns an empty drawing.
/// @throws OptionError (validate.h) for options out of range or a cloud estimated to need more than max_memory_gb;
/// pcsketch::Cancelled if the progress callback asks to
/// stop.
Prepared prepare(PointCloud cloud, const DrawOptions& options = {});

/// A drawing of one view, with what it cost.
struct DrawResult {
  Drawing drawing;
  Timings timings;  ///< this view's stages only (prepare()'s are in Prepared::timings)
  Warnings warnings;
};

/// Draws `prepared` as seen by `camera`: contours, visibility of every line, stroke thickness, shadow hatching.
/// `options.camera` is ignored (the camera argument replaces it); the drawing's `parameters` record every option.
DrawResult draw_view(const Prepared& prepared, const view::CameraOptions& camera, const DrawOptions& options = {});

/// prepare() then draw_view() with options.camera. Timings and warnings of both steps.
DrawResult draw(PointCloud cloud, const DrawOptions& options = {});

/// The views of technical drawing on one page (page::compose_sheet): front, top, side and iso from one analysis,
/// front, top and side at one scale and aligned, in the first- or third-angle arrangement. `camera` gives the up
/// direction, the size of each view and the margin; its direction of sight is not used. With options.page.scale the
/// page scale is that of the aligned views.
DrawResult draw_sheet(const Prepared& prepared, const view::CameraOptions& camera, page::Arrangement arrangement,
                      const DrawOptions& options = {});

/// File stems of the paper's Fig. 19 columns, in order (stage_drawings; the CLI checks -o against them).
inline constexpr std::array<std::string_view, 5> kStageNames = {"b_contours", "c_ridges_valleys", "d_fused",
                                                                "e_thickness", "f_shadow"};

/// The paper's Fig. 19 columns of one view, and what computing them took and reported.
struct StageDrawings {
  std::vector<std::pair<std::string, Drawing>> stages;  ///< (file stem such as "b_contours", drawing), in order
  Timings timings;    ///< the view's stages (computed once for all five)
  Warnings warnings;  ///< the view's and the shading's: the same draw_view reports for this camera
};

/// The paper's Fig. 19 columns for one view: (b) contours, (c) ridge-valley lines, (d) both fused (constant width),
/// (e) with thickness, (f) with shadow. The view is computed once and styled five times.
StageDrawings stage_drawings(const Prepared& prepared, const view::CameraOptions& camera,
                             const DrawOptions& options = {});

}  // namespace pcsketch
