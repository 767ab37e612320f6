#include <algorithm>
#include <array>
#include <cctype>
#include <nlohmann/json.hpp>

#include "pcsketch/core/error.h"
#include "pcsketch/page/page.h"

namespace pcsketch::page {

namespace {

constexpr std::size_t kFront = 0, kTop = 1, kSide = 2, kIso = 3;

/// The quarter (column, row) of each view, in sheet_views order. Third angle: top above front, right view right of
/// it, iso top right. First angle: top below front, left view right of it, iso bottom right.
std::array<std::array<int, 2>, 4> quarters(Arrangement a) {
  if (a == Arrangement::ThirdAngle) return {{{0, 1}, {0, 0}, {1, 1}, {1, 0}}};
  return {{{0, 0}, {0, 1}, {1, 0}, {1, 1}}};
}

/// The image points of `d` scaled by `zoom` about the image centre, then moved by `offset`.
void place(Drawing& d, float zoom, const Vec2f& offset) {
  const Vec2f centre(0.5f * static_cast<float>(d.width), 0.5f * static_cast<float>(d.height));
  const auto move = [&](Vec2f& p) { p = offset + centre + zoom * (p - centre); };
  for (Stroke& s : d.strokes)
    for (Vec2f& p : s.image_points) move(p);
  for (ShadeRegion& r : d.regions)
    for (Vec2f& p : r.polygon) move(p);
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

std::string_view to_string(Arrangement a) { return a == Arrangement::ThirdAngle ? "third" : "first"; }

std::optional<Arrangement> parse_arrangement(std::string_view name) {
  if (name == "third") return Arrangement::ThirdAngle;
  if (name == "first") return Arrangement::FirstAngle;
  return std::nullopt;
}

std::vector<view::NamedView> sheet_views(Arrangement a) {
  using view::NamedView;
  return {NamedView::Front, NamedView::Top, a == Arrangement::ThirdAngle ? NamedView::Right : NamedView::Left,
          NamedView::Iso};
}

std::pair<Drawing, double> compose_sheet(std::vector<SheetView> views, Arrangement arrangement) {
  if (views.size() != 4) throw Error("page: a sheet has 4 views, got " + std::to_string(views.size()));
  const int w = views[0].drawing.width, h = views[0].drawing.height;
  for (const SheetView& v : views)
    if (v.drawing.width != w || v.drawing.height != h || !(v.camera.scale > 0) ||
        v.camera.projection != view::Projection::Orthographic)
      throw Error("page: the views of a sheet must be orthographic and of one size");
  // Each view was framed to fill its image: the three aligned views take the smallest of their scales.
  const double scale = std::min({views[kFront].camera.scale, views[kTop].camera.scale, views[kSide].camera.scale});
  Drawing sheet;
  sheet.width = 2 * w;
  sheet.height = 2 * h;
  sheet.origin = views[kFront].drawing.origin;
  sheet.parameters = views[kFront].drawing.parameters;
  sheet.parameters["sheet"] = to_string(arrangement);
  sheet.camera = {{"sheet", to_string(arrangement)}, {"views", nlohmann::json::array()}};
  const auto cells = quarters(arrangement);
  const float label_size = 0.025f * static_cast<float>(std::min(w, h));
  for (std::size_t i = 0; i < views.size(); ++i) {
    Drawing& d = views[i].drawing;
    const float zoom = i == kIso ? 1.f : static_cast<float>(scale / views[i].camera.scale);
    const Vec2f offset(static_cast<float>(cells[i][0] * w), static_cast<float>(cells[i][1] * h));
    place(d, zoom, offset);
    sheet.camera["views"].push_back({{"view", view::to_string(views[i].name)},
                                     {"camera", d.camera},
                                     {"offset", {offset.x(), offset.y()}},
                                     {"zoom", zoom}});
    // Strokes keep their fused_into links, shifted by the strokes before them.
    const auto shift = static_cast<std::uint32_t>(sheet.strokes.size());
    for (Stroke& s : d.strokes) {
      if (s.fused_into) *s.fused_into += shift;
      sheet.strokes.push_back(std::move(s));
    }
    sheet.regions.insert(sheet.regions.end(), std::make_move_iterator(d.regions.begin()),
                         std::make_move_iterator(d.regions.end()));
    sheet.annotations.labels.push_back(
        {offset + Vec2f(0.05f * static_cast<float>(w), static_cast<float>(h) - 0.5f * label_size),
         upper(view::to_string(views[i].name)), label_size, Label::Anchor::Start});
  }
  sheet.annotations.labels.push_back({Vec2f(static_cast<float>(2 * w) - 0.05f * static_cast<float>(w),
                                            static_cast<float>(2 * h) - 0.5f * label_size),
                                      std::string(to_string(arrangement)) + "-angle projection", label_size,
                                      Label::Anchor::End});
  return {std::move(sheet), scale};
}

}  // namespace pcsketch::page
