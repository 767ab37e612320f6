// CLI11 flags generated from the option table (pcsketch/options_table.h): each value is checked against the
// entry's range while parsing, so a bad value is a bad command line (exit 1) with the library's own message.

#include <nlohmann/json.hpp>

#include "options.h"
#include "pcsketch/core/error.h"
#include "views.h"

namespace pcsketch::cli {

namespace {

/// `value` checked and stored: a bad one becomes a CLI11 validation error carrying the library's message.
void apply(const options::Option& option, DrawOptions& o, const nlohmann::json& value) {
  try {
    options::check(option, value);
    option.set(o, value);
  } catch (const Error& e) {
    throw CLI::ValidationError(e.what());
  }
}

/// The value --help shows: names without quotes, nothing for an unset optional.
std::string shown(const nlohmann::json& value) {
  if (value.is_null()) return "";
  return value.is_string() ? value.get<std::string>() : value.dump();
}

CLI::Option* bind(CLI::App* cmd, const options::Option& opt, DrawOptions& o) {
  const std::string help = opt.unit.empty() ? opt.help : opt.help + " (" + opt.unit + ")";
  const std::string names = opt.alias.empty() ? opt.flag : opt.flag + "," + opt.alias;
  switch (opt.type) {
    case options::Type::Bool:
      // No default shown: "--no-brush{false}" would read as the opposite of what the flag does.
      return cmd->add_flag_function(
          names, [&opt, &o](std::int64_t) { apply(opt, o, !opt.negated); }, help);
    case options::Type::Integer:
      return cmd->add_option_function<std::int64_t>(
          names, [&opt, &o](const std::int64_t& v) { apply(opt, o, v); }, help);
    case options::Type::Number:
      return cmd->add_option_function<double>(
          names, [&opt, &o](const double& v) { apply(opt, o, v); }, help);
    case options::Type::Choice:
      return cmd
          ->add_option_function<std::string>(
              names, [&opt, &o](const std::string& v) { apply(opt, o, v); }, help)
          ->check(CLI::IsMember(opt.choices));
    case options::Type::List:
      return cmd
          ->add_option_function<std::vector<double>>(
              names, [&opt, &o](const std::vector<double>& v) { apply(opt, o, v); }, help)
          ->expected(1, 16);
    case options::Type::Vector:
      return add_vec3(cmd, names, help, [&opt, &o](const Vec3d& v) {
        apply(opt, o, nlohmann::json::array({v.x(), v.y(), v.z()}));
      });
    case options::Type::Custom:
      break;
  }
  throw Error(opt.key + ": the option table cannot bind a flag of this type");
}

}  // namespace

void add_table_flags(CLI::App* cmd, DrawOptions& o, const std::function<bool(const options::Option&)>& wanted) {
  for (const options::Option& opt : options::table()) {
    if (opt.flag.empty() || opt.cli != options::Cli::Table || !wanted(opt)) continue;
    CLI::Option* flag = bind(cmd, opt, o)->group(opt.group);
    if (opt.type != options::Type::Bool) flag->default_str(shown(opt.get(o)));
  }
}

}  // namespace pcsketch::cli
