#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "pcsketch/core/error.h"
#include "pcsketch/page/page.h"

namespace pcsketch::page {

namespace {

// The band under the drawing that holds the scale bar and the north arrow, as a fraction of the smaller image side.
constexpr double kBandFraction = 0.08;
// Left and right inset of the band's contents, fraction of the smaller side (the camera's default margin).
constexpr double kInsetFraction = 0.05;
// The scale bar is the roundest length (1, 2 or 5 × 10^k units) up to this fraction of the drawing's width.
constexpr double kBarFraction = 0.3;

std::string figure(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

/// "1:20" for 0.05, "2:1" for 2.
std::string ratio_text(double scale) { return scale <= 1 ? "1:" + figure(1 / scale) : figure(scale) + ":1"; }

/// The roundest length of 1, 2 or 5 × 10^k at most `limit`, and how many cells its bar has.
std::pair<double, int> round_length(double limit) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (const int lead : {5, 2, 1})
    if (lead * decade <= limit * (1 + 1e-9)) return {lead * decade, lead == 2 ? 4 : 5};
  return {decade, 5};
}

/// A bar of alternating filled and open cells, its figures above, the stated scale under it.
void add_scale_bar(Annotations& a, double left, double base, double band, double pixels_per_unit, double image_width,
                   const PageOptions& o) {
  const auto [length, cells] = round_length(kBarFraction * image_width / pixels_per_unit);
  const float x0 = static_cast<float>(left);
  const float x1 = static_cast<float>(left + length * pixels_per_unit);
  const float top = static_cast<float>(base - 0.1 * band);
  const float bottom = static_cast<float>(base);
  a.lines.push_back({{x0, top}, {x1, top}, {x1, bottom}, {x0, bottom}, {x0, top}});
  for (int c = 0; c < cells; c += 2) {
    const float l = x0 + (x1 - x0) * static_cast<float>(c) / static_cast<float>(cells);
    const float r = x0 + (x1 - x0) * static_cast<float>(c + 1) / static_cast<float>(cells);
    a.fills.push_back({{l, top}, {r, top}, {r, bottom}, {l, bottom}});
  }
  const float size = static_cast<float>(0.2 * band);
  const std::string unit = o.units == Units::None ? "" : " " + std::string(to_string(o.units));
  a.labels.push_back({{x0, top - 0.4f * size}, "0", size, Label::Anchor::Middle});
  a.labels.push_back({{x1, top - 0.4f * size}, figure(length) + unit, size, Label::Anchor::Middle});
  if (o.scale) a.labels.push_back({{x0, bottom + 1.3f * size}, ratio_text(*o.scale), size, Label::Anchor::Start});
}

/// An arrow along `north` (image direction) centred at `centre`, "N" beyond its head.
void add_north_arrow(Annotations& a, const Vec2f& centre, const Vec2f& north, double band) {
  const Vec2f dir = north.normalized();
  const Vec2f side(-dir.y(), dir.x());
  const float half = static_cast<float>(0.2 * band);
  const Vec2f tail = centre - half * dir;
  const Vec2f tip = centre + half * dir;
  const float head = 0.35f * half;
  a.lines.push_back({tail, tip - head * dir});
  a.fills.push_back({tip, tip - 1.6f * head * dir + head * side, tip - 1.6f * head * dir - head * side});
  const float size = static_cast<float>(0.2 * band);
  a.labels.push_back({tip + 0.9f * size * dir + Vec2f(0.f, 0.35f * size), "N", size, Label::Anchor::Middle});
}

}  // namespace

std::string_view to_string(Units units) {
  switch (units) {
    case Units::Millimetre: return "mm";
    case Units::Centimetre: return "cm";
    case Units::Metre: return "m";
    case Units::None: break;
  }
  return "";
}

double millimetres(Units units) {
  switch (units) {
    case Units::Millimetre: return 1;
    case Units::Centimetre: return 10;
    case Units::Metre: return 1000;
    case Units::None: break;
  }
  return 0;
}

double parse_scale(std::string_view text) {
  const std::size_t colon = text.find(':');
  double page = 0, model = 0;
  const auto read = [](std::string_view s, double& v) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size() && std::isfinite(v) && v > 0;
  };
  if (colon == std::string_view::npos || !read(text.substr(0, colon), page) || !read(text.substr(colon + 1), model))
    throw Error("expected a scale such as 1:20 (page length : model length, both positive), got '" +
                std::string(text) + "'");
  return page / model;
}

std::optional<Vec2f> north_in_image(const view::Camera& camera) {
  // Image u runs along camera.right, v down along −camera.up; the model's +y axis seen in the image.
  const Vec2f north(camera.right.y(), -camera.up.y());
  if (north.norm() < 0.2f) return std::nullopt;  // looking within about 12° of the y axis: no direction to show
  return north.normalized();
}

Warnings annotate(Drawing& d, double pixels_per_unit, const std::optional<Vec2f>& north, const PageOptions& o) {
  Warnings warnings;
  if (!(pixels_per_unit > 0) || !std::isfinite(pixels_per_unit))
    throw Error("page: pixels per model unit must be positive");
  if (o.scale) d.page_mm_per_pixel = *o.scale * millimetres(o.units) / pixels_per_unit;
  const bool arrow = o.north_arrow && north;
  if (o.north_arrow && !north) warnings.push_back("--north-arrow: the view looks along the y axis: no arrow drawn");
  if (!o.scale_bar && !arrow) return warnings;
  const double side = std::min(d.width, d.height);
  const double band = std::max(24.0, std::round(kBandFraction * side));
  const double top = d.height;
  d.height += static_cast<int>(band);
  const double inset = kInsetFraction * side;
  d.annotations.width = static_cast<float>(std::max(1.0, band / 60));
  if (o.scale_bar) add_scale_bar(d.annotations, inset, top + 0.6 * band, band, pixels_per_unit, d.width, o);
  if (arrow)
    add_north_arrow(d.annotations, Vec2f(static_cast<float>(d.width - inset - 0.25 * band),
                                         static_cast<float>(top + 0.6 * band)),
                    *north, band);
  return warnings;
}

}  // namespace pcsketch::page
