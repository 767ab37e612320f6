// The page flags of `draw`: stated scale, the model's unit, scale bar and north arrow.

#include "options.h"
#include "pcsketch/core/error.h"

namespace pcsketch::cli {

void add_page_options(CLI::App* cmd, page::PageOptions& page) {
  const std::string group = "Page and scale";
  cmd->add_option_function<std::string>(
         "--scale",
         [&page](const std::string& text) {
           try {
             page.scale = page::parse_scale(text);
           } catch (const Error& e) {
             throw CLI::ValidationError("--scale", e.what());
           }
         },
         "Draw at this scale, page : model, e.g. 1:20 (needs --units; orthographic views): the SVG/PDF page is "
         "sized from the model instead of --page-width-mm")
      ->group(group);
  add_enum(cmd, "--units", page.units,
           {{"mm", page::Units::Millimetre}, {"cm", page::Units::Centimetre}, {"m", page::Units::Metre}},
           "Unit of the model's coordinates, for --scale and the scale bar's figures")
      ->group(group);
  cmd->add_flag("--scale-bar", page.scale_bar,
                "A scale bar (a round length in model units) and the stated scale, in a band under the drawing, "
                "layer '8 annotations'")
      ->group(group);
  cmd->add_flag("--north-arrow", page.north_arrow,
                "An arrow along the model's +y axis (north for georeferenced scans) beside the scale bar")
      ->group(group);
}

}  // namespace pcsketch::cli
