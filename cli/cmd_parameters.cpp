// pcsketch parameters --markdown: docs/parameters.md, generated from the option table (hidden: a maintainer's tool;
// the ctest docs.parameters_current fails when the checked-in file differs).

#include <iostream>

#include "commands.h"
#include "pcsketch/options_table.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {

void add_parameters_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("parameters", "Every drawing option as a Markdown table (docs/parameters.md)");
  cmd->group("");  // hidden from --help
  auto markdown = std::make_shared<bool>(false);
  cmd->add_flag("--markdown", *markdown, "Write docs/parameters.md to stdout");
  cmd->callback([markdown] {
    if (!*markdown) throw OptionError("parameters", "give --markdown");
    std::cout << options::markdown();
  });
}

}  // namespace pcsketch::cli
