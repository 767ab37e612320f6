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

double mm_per_pixel(int image_width, const RenderOptions& o) {
  return o.page_width_mm && image_width > 0 ? *o.page_width_mm / image_width : 25.4 / 96.0;
}

float pen_width_px(int image_width, const RenderOptions& o) {
  return o.pen_width ? *o.pen_width : static_cast<float>(o.pen_width_mm / mm_per_pixel(image_width, o));
}

}  // namespace pcsketch::render
