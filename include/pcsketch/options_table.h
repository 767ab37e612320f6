#pragma once
// Every option of DrawOptions described once: its JSON key (the member path), CLI flag, unit, range and help. The
// JSON record of a drawing, its replay (from_json), validate(), the CLI flags, the Python keywords and
// docs/parameters.md are all generated from this one table.

#include <functional>
#include <limits>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace pcsketch {

struct DrawOptions;

namespace options {

/// How a value is spelled on the command line and in JSON.
enum class Type {
  Bool,     ///< true/false; a flag without value on the command line
  Integer,  ///< a whole number
  Number,   ///< a real number
  Choice,   ///< one of Option::choices (a string)
  List,     ///< one or more numbers
  Vector,   ///< three numbers X,Y,Z
  Custom,   ///< a small object or pair of numbers: JSON only, or a hand-written flag
};

/// A closed or half-open interval of allowed numbers; unbounded by default. Every number must also be finite.
struct Range {
  double lo = -std::numeric_limits<double>::max();
  double hi = std::numeric_limits<double>::max();
  bool lo_open = false;  ///< lo itself is refused: (lo, hi]
  bool hi_open = false;  ///< hi itself is refused: [lo, hi)
};

/// Where the CLI flag comes from.
enum class Cli {
  Table,        ///< bound from this entry (cli/option_flags.cpp)
  HandWritten,  ///< `flag` sets it but needs its own parser (--size, --view, --file-normals, …): cli/views.cpp, …
};

/// One option.
struct Option {
  std::string key;   ///< JSON path in DrawOptions::to_json, the member path: "features.detection.ridge_threshold_alpha"
  std::string flag;  ///< CLI flag ("--alpha"); empty: set from JSON (--config) or C++ only
  std::string alias;  ///< a second name of the flag ("--pen-width" for "--pen-width-mm"); empty: none
  std::string group;  ///< --help section and docs/parameters.md heading
  Type type = Type::Number;
  bool nullable = false;  ///< std::optional: null (JSON) or absent (CLI) leaves it unset
  bool negated = false;   ///< a Bool whose flag turns it off (--no-brush clears thickness.brush)
  Cli cli = Cli::Table;
  Range range;
  std::vector<std::string> choices;  ///< Type::Choice: the names, in enum order
  std::string unit;
  std::string help;
  std::function<nlohmann::json(const DrawOptions&)> get;         ///< the value as JSON (null when unset)
  std::function<void(DrawOptions&, const nlohmann::json&)> set;  ///< @throws Error for a value of the wrong type

  /// What messages call it: the flag, else the key.
  const std::string& name() const { return flag.empty() ? key : flag; }
};

/// Every option of DrawOptions (not progress), in --help order.
const std::vector<Option>& table();

/// Checks one JSON value against the option's range (each element of a list or vector) and finiteness.
/// @throws OptionError naming Option::name(), e.g. "--alpha: must be in (0, 1), got 0".
void check(const Option& option, const nlohmann::json& value);

/// Every option as nested objects keyed by the member path.
nlohmann::json to_json(const DrawOptions& options);

/// Sets the options named in `json` (nested as to_json writes them); keys it does not hold keep their value in
/// `options`. `resolved` (the values a drawing computed) is ignored. @throws Error naming the key for an unknown key
/// or a value of the wrong type. Ranges are checked by validate(), not here.
void from_json(const nlohmann::json& json, DrawOptions& options);

/// docs/parameters.md: one table per group (flag, key, default, range, unit, help).
std::string markdown();

}  // namespace options
}  // namespace pcsketch
