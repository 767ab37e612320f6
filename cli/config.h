#pragma once
// pcsketch draw --config FILE: replaying the options recorded with a drawing, command-line flags taking precedence.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "pcsketch/pipeline.h"

namespace pcsketch::cli {

/// The options recorded in `path`: a drawing's SVG (the `parameters` in its <desc>), a JSON export (its
/// `parameters`) or the options alone (what --print-config writes). @throws Error naming the file.
nlohmann::json read_config(const std::string& path);

/// `parsed` with every option that no flag given to `cmd` set taken from `config` (a read_config() result; options
/// it does not name keep their defaults). @throws Error naming `path` for an unknown option or a bad value in it.
DrawOptions with_config(const nlohmann::json& config, const std::string& path, const DrawOptions& parsed,
                        const CLI::App& cmd);

}  // namespace pcsketch::cli
