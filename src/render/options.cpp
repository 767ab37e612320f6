#include "pcsketch/render/options.h"

#include <nlohmann/json.hpp>

namespace pcsketch::render {

nlohmann::json RenderOptions::to_json() const {
  nlohmann::json j = {{"hidden_lines", hidden_lines == HiddenLines::Dashed ? "dashed" : "none"},
                      {"plotter", plotter},
                      {"pen_width", pen_width},
                      {"default_width", default_width},
                      {"width_step", width_step},
                      {"hidden_width", hidden_width},
                      {"hidden_grey", hidden_grey},
                      {"hidden_dash", hidden_dash},
                      {"shading", shading},
                      {"decimals", decimals}};
  j["page_width_mm"] = page_width_mm ? nlohmann::json(*page_width_mm) : nlohmann::json(nullptr);
  return j;
}

}  // namespace pcsketch::render
