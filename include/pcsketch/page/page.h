#pragma once
// The page around the model's lines: a stated scale (1:20 in the model's units), a scale bar and a north arrow, and
// the sheet of technical drawing (front, top, side and iso views aligned on one page).

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/core/report.h"
#include "pcsketch/view/camera.h"

namespace pcsketch::page {

/// The unit of the model's coordinates (a scan's are usually metres, a CAD part's millimetres).
enum class Units { None, Millimetre, Centimetre, Metre };

/// "mm", "cm", "m" ("" for None), as on the command line.
std::string_view to_string(Units units);
/// Millimetres in one model unit (0 for None).
double millimetres(Units units);

struct PageOptions {
  /// Stated scale, page length ÷ model length (1:20 is 0.05): the page's size follows from the view's pixels per
  /// model unit instead of fitting the image to the page. Needs `units` and an orthographic view. Unset: no scale.
  std::optional<double> scale;
  Units units = Units::None;  ///< the model's unit: needed for `scale`, labels the scale bar
  /// A scale bar (a round length, about a fifth of the drawing's width) in a band added under the drawing.
  bool scale_bar = false;
  /// A north arrow, pointing along the model's +y axis as seen in the view (georeferenced scans: y is north).
  bool north_arrow = false;
};

/// "1:20" → 0.05 (page ÷ model); "2:1" → 2. @throws pcsketch::Error for anything but two positive numbers.
double parse_scale(std::string_view text);

/// Fixes the page scale of `drawing` and adds its scale bar and north arrow (Drawing::annotations), in a band added
/// under the drawing so that they never cover a line. `pixels_per_unit` is the view's scale (an orthographic
/// camera's Camera::scale); `north` the image direction of the model's +y axis (unset: not shown in this view).
/// Nothing changes when no option asks for it. Returns warnings (a north arrow that cannot be drawn).
Warnings annotate(Drawing& drawing, double pixels_per_unit, const std::optional<Vec2f>& north,
                  const PageOptions& options);

/// The image direction of the model's +y axis in `camera` (orthographic), or nothing when the view looks nearly
/// along y.
std::optional<Vec2f> north_in_image(const view::Camera& camera);

/// How the views of a sheet are arranged. Third angle (ASME): the top view above the front, the right view on its
/// right. First angle (ISO, Europe): the top view below the front, the left view on its right.
enum class Arrangement { ThirdAngle, FirstAngle };

std::string_view to_string(Arrangement arrangement);
std::optional<Arrangement> parse_arrangement(std::string_view name);

/// The views of a sheet, in this order: front, top, side (right for third angle, left for first), iso.
std::vector<view::NamedView> sheet_views(Arrangement arrangement);

/// One view of a sheet: its drawing and the orthographic camera that made it.
struct SheetView {
  view::NamedView name = view::NamedView::Front;
  Drawing drawing;
  view::Camera camera;
};

/// The views on one page of twice the views' width and height, one per quarter. Front, top and side are redrawn at
/// one scale (the smallest of the three, so each fits its quarter) and aligned: the top view shares the front's
/// columns, the side view its rows. The iso view keeps its own scale. Line widths stay as drawn. Each view is named
/// under it. Returns the sheet drawing and the common scale in pixels per model unit.
/// @param views front, top, side, iso (sheet_views order), all of one image size
std::pair<Drawing, double> compose_sheet(std::vector<SheetView> views, Arrangement arrangement);

}  // namespace pcsketch::page
