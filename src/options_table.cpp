#include "pcsketch/options_table.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "options_fields.h"
#include "pcsketch/validate.h"

namespace pcsketch::options {

namespace {

constexpr double kHuge = std::numeric_limits<double>::max();

std::string range_text(const Range& r) {
  return (r.lo_open ? "(" : "[") + (r.lo == -kHuge ? std::string("-inf") : number(r.lo)) + ", " +
         (r.hi == kHuge ? "inf)" : number(r.hi) + (r.hi_open ? ")" : "]"));
}

void check_number(const Option& option, double value) {
  const Range& r = option.range;
  if (!std::isfinite(value)) throw OptionError(option.name(), "must be a finite number, got " + number(value));
  const bool ok = (r.lo_open ? value > r.lo : value >= r.lo) && (r.hi_open ? value < r.hi : value <= r.hi);
  if (!ok) throw OptionError(option.name(), "must be in " + range_text(r) + ", got " + number(value));
}

nlohmann::json::json_pointer pointer(const std::string& key) {
  std::string path = "/" + key;
  std::replace(path.begin(), path.end(), '.', '/');
  return nlohmann::json::json_pointer(path);
}

/// The entry of `key` (a JSON path), or nullptr.
const Option* find_key(const std::string& key) {
  for (const Option& o : table())
    if (o.key == key) return &o;
  return nullptr;
}

/// Sets every option under `json`, whose path in the options is `prefix` ("" at the top).
void read_object(const nlohmann::json& json, const std::string& prefix, DrawOptions& options) {
  if (!json.is_object()) throw Error((prefix.empty() ? "the options" : prefix) + ": expected an object");
  for (const auto& [name, value] : json.items()) {
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (key == "resolved") continue;  // what a drawing computed, not an option
    if (const Option* option = find_key(key)) {
      option->set(options, value);
      continue;
    }
    const bool inner =
        std::any_of(table().begin(), table().end(), [&](const Option& o) { return o.key.starts_with(key + "."); });
    if (!inner) throw Error(key + ": no such option (docs/parameters.md lists them)");
    read_object(value, key, options);
  }
}

/// A default value as docs/parameters.md shows it: names without quotes, unset as "unset".
std::string default_text(const nlohmann::json& value) {
  if (value.is_null()) return "unset";
  return value.is_string() ? value.get<std::string>() : value.dump();
}

/// A table cell: pipes escaped.
std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

const std::vector<Option>& table() {
  static const std::vector<Option> entries = [] {
    std::vector<Option> out;
    detail::Builder builder(out);
    detail::add_analysis_options(builder);
    detail::add_drawing_options(builder);
    return out;
  }();
  return entries;
}

void check(const Option& option, const nlohmann::json& value) {
  if (value.is_number()) check_number(option, value.get<double>());
  if (value.is_array())
    for (const nlohmann::json& item : value)
      if (item.is_number()) check_number(option, item.get<double>());
}

nlohmann::json to_json(const DrawOptions& options) {
  nlohmann::json out = nlohmann::json::object();
  for (const Option& o : table()) out[pointer(o.key)] = o.get(options);
  return out;
}

void from_json(const nlohmann::json& json, DrawOptions& options) { read_object(json, "", options); }

std::string markdown() {
  const DrawOptions defaults;
  std::string out =
      "# Parameters\n\nEvery option of a drawing (`DrawOptions`), generated from the option table "
      "(`src/options_*.cpp`) by `pcsketch parameters --markdown`: do not edit by hand. *Key* is the JSON path in the "
      "`parameters` a drawing records and in `pcsketch draw --config`; options without a flag are set there or "
      "from C++. Lengths in *h* are multiples of the cloud's mean point spacing. Flags marked (off) clear the "
      "option.\n";
  std::string group;
  for (const Option& o : table()) {
    if (o.group != group) {
      group = o.group;
      out += "\n## " + group + "\n\n| Flag | Key | Default | Range | Unit | Meaning |\n|---|---|---|---|---|---|\n";
    }
    const std::string flag = o.flag.empty() ? ""
                             : "`" + o.flag + "`" + (o.alias.empty() ? "" : " or `" + o.alias + "`") +
                                   (o.negated ? " (off)" : "");
    const bool ranged = o.range.lo != -kHuge || o.range.hi != kHuge;
    std::string range = ranged ? range_text(o.range) : "";
    if (o.type == Type::Choice) {
      for (const std::string& c : o.choices) range += (range.empty() ? "" : ", ") + c;
    }
    out += "| " + flag + " | `" + o.key + "` | " + cell(default_text(o.get(defaults))) + " | " + range + " | " +
           o.unit + " | " + cell(o.help) + " |\n";
  }
  return out;
}

}  // namespace pcsketch::options
