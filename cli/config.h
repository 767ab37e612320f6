#pragma once
// pcsketch draw --config FILE: replaying the options recorded with a drawing, command-line flags taking precedence.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "pcsketch/pipeline.h"

namespace pcsketch::cli {

/// The options recorded in `path`: a drawing's SVG (the `parameters` in its <desc>), a JSON export (its
/// `parameters`) or the options alone (what --print-config writes). @throws Error naming the file.
nlohmann::json read_config(const std::string& path);

/// `parsed` with every option that no flag given to `cmd` set taken from `config` (a read_config() result; options
/// it does not name keep their defaults). @throws Error naming `path` for an unknown option or a bad value in it.
/// The arrangement a sheet's drawing records beside its options ("sheet": "first" or "third"), taken out of
/// `config`; nothing for a drawing of one view. @throws Error naming `path` for another value.
std::optional<page::Arrangement> take_sheet(nlohmann::json& config, const std::string& path);

/// Whether a flag choosing the direction of sight (--view, --azimuth, --views, …) was given to `cmd`.
bool sight_flag_given(const CLI::App& cmd);

DrawOptions with_config(const nlohmann::json& config, const std::string& path, const DrawOptions& parsed,
                        const CLI::App& cmd);

}  // namespace pcsketch::cli
