// The page flag the option table cannot bind: --scale reads a ratio such as 1:20.

#include "options.h"
#include "pcsketch/core/error.h"

namespace pcsketch::cli {

void add_scale_option(CLI::App* cmd, page::PageOptions& page) {
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
      ->group("Page and scale");
}

}  // namespace pcsketch::cli
