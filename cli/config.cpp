#include "config.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <sstream>

#include "pcsketch/core/error.h"
#include "pcsketch/options_table.h"
#include "pcsketch/validate.h"

namespace pcsketch::cli {

namespace {

/// The flags that choose the direction of sight (cli/views.cpp) and the camera fields that hold it.
constexpr std::array<const char*, 7> kSightFlags = {"--view",   "--azimuth", "--elevation", "--eye",
                                                    "--target", "--views",   "--turntable"};
constexpr std::array<std::string_view, 6> kSightKeys = {"camera.direction",     "camera.named", "camera.azimuth_deg",
                                                        "camera.elevation_deg", "camera.eye",   "camera.target"};

/// The text of an SVG's <desc>, with the four entities the SVG writer escapes (render/svg.cpp) undone.
std::string svg_desc(const std::string& svg, const std::string& path) {
  const std::size_t open = svg.find("<desc>"), close = svg.find("</desc>");
  if (open == std::string::npos || close == std::string::npos || close < open)
    throw Error(FileLoc{path, {}, {}}, "no <desc> with recorded parameters: not an SVG written by pcsketch");
  const std::string_view text = std::string_view(svg).substr(open + 6, close - open - 6);
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '&') {
      out += text[i];
      continue;
    }
    const std::size_t end = text.find(';', i);
    const std::string_view entity = text.substr(i, end == std::string_view::npos ? 1 : end - i + 1);
    const char c = entity == "&amp;"    ? '&'
                   : entity == "&lt;"   ? '<'
                   : entity == "&gt;"   ? '>'
                   : entity == "&quot;" ? '"'
                                        : 0;
    if (c == 0) throw Error(FileLoc{path, {}, {}}, "unexpected XML entity " + quote(entity) + " in <desc>");
    out += c;
    i += entity.size() - 1;
  }
  return out;
}

}  // namespace

bool sight_flag_given(const CLI::App& cmd) {
  return std::any_of(kSightFlags.begin(), kSightFlags.end(), [&](const char* name) {
    const CLI::Option* flag = cmd.get_option_no_throw(name);
    return flag != nullptr && flag->count() > 0;
  });
}

std::optional<page::Arrangement> take_sheet(nlohmann::json& config, const std::string& path) {
  if (!config.is_object() || !config.contains("sheet")) return std::nullopt;
  const nlohmann::json value = config["sheet"];
  config.erase("sheet");
  const auto arrangement = value.is_string() ? page::parse_arrangement(value.get<std::string>()) : std::nullopt;
  if (!arrangement) throw Error(FileLoc{path, {}, {}}, "sheet: expected \"first\" or \"third\", got " + value.dump());
  return arrangement;
}

nlohmann::json read_config(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(FileLoc{path, {}, {}}, "cannot read the config file");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string content = text.str();
  const std::size_t first = content.find_first_not_of(" \t\r\n");
  const bool svg = first != std::string::npos && content[first] == '<';
  const nlohmann::json j = nlohmann::json::parse(svg ? svg_desc(content, path) : content, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw Error(FileLoc{path, {}, {}}, std::string("not valid JSON") + (svg ? " in <desc>" : "") +
                                           ": expected a drawing (SVG or JSON) or an options file");
  if (svg || j.contains("parameters")) {
    if (!j.contains("parameters") || !j["parameters"].is_object())
      throw Error(FileLoc{path, {}, {}}, "no recorded \"parameters\" object");
    return j["parameters"];
  }
  return j;
}

DrawOptions with_config(const nlohmann::json& config, const std::string& path, const DrawOptions& parsed,
                        const CLI::App& cmd) {
  DrawOptions recorded;
  try {
    options::from_json(config, recorded);
  } catch (const Error& e) {
    throw Error(FileLoc{path, {}, {}}, e.what());
  }
  DrawOptions out = parsed;  // keeps what is not an option (the progress callback)
  // The direction of sight is one choice made by several flags: any of them given replaces the recorded one whole
  // (a recorded --view left with --azimuth 30 given would otherwise be two sights).
  const bool sight_given = sight_flag_given(cmd);
  for (const options::Option& o : options::table()) {
    const CLI::Option* flag = o.flag.empty() ? nullptr : cmd.get_option_no_throw(o.flag);
    if (flag != nullptr && flag->count() > 0) continue;
    if (sight_given && std::find(kSightKeys.begin(), kSightKeys.end(), o.key) != kSightKeys.end()) continue;
    try {
      options::check(o, o.get(recorded));  // a bad recorded value is the file's fault, not the command line's
    } catch (const OptionError& e) {
      throw Error(FileLoc{path, {}, {}}, e.what());
    }
    o.set(out, o.get(recorded));
  }
  return out;
}

}  // namespace pcsketch::cli
