#include "pcsketch/render/options.h"

#include <nlohmann/json.hpp>

namespace pcsketch::render {

nlohmann::json RenderOptions::to_json() const {
  nlohmann::json j = {{"hidden_lines", hidden_lines == HiddenLines::Dashed ? "dashed" : "none"},
                      {"plotter", plotter},
                      {"pen_width_mm", pen_width_mm},
                      {"default_width", default_width},
                      {"width_step", width_step},
                      {"hidden_width", hidden_width},
                      {"hidden_grey", hidden_grey},
                      {"hidden_dash", hidden_dash},
                      {"shading", shading},
                      {"decimals", decimals}};
  j["pen_width_px"] = pen_width ? nlohmann::json(*pen_width) : nlohmann::json(nullptr);
  j["page_width_mm"] = page_width_mm ? nlohmann::json(*page_width_mm) : nlohmann::json(nullptr);
  return j;
}

double mm_per_pixel(const Drawing& d, const RenderOptions& o) {
  if (d.page_mm_per_pixel) return *d.page_mm_per_pixel;
  return o.page_width_mm && d.width > 0 ? *o.page_width_mm / d.width : 25.4 / 96.0;
}

bool page_in_mm(const Drawing& d, const RenderOptions& o) { return d.page_mm_per_pixel || o.page_width_mm; }

float pen_width_px(const Drawing& d, const RenderOptions& o) {
  return o.pen_width ? *o.pen_width : static_cast<float>(o.pen_width_mm / mm_per_pixel(d, o));
}

}  // namespace pcsketch::render
