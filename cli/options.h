#pragma once
// Flag blocks shared by several subcommands: one registration per option struct, so `features` and `draw` accept
// the same names, checks and defaults and describe them in the same words.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pcsketch/differential/surface.h"
#include "pcsketch/features/ridge_valley_lines.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/pipeline.h"

namespace pcsketch::cli {

/// A flag taking one of the names of `names`, stored into `target` (enum values print badly through CLI11's
/// transformers when the enum is a uint8_t, so the names are looked up here). Any other name is a usage error.
template <class Enum>
CLI::Option* add_enum(CLI::App* cmd, const std::string& name, Enum& target, const std::map<std::string, Enum>& names,
                      const std::string& help) {
  std::vector<std::string> keys;
  for (const auto& entry : names) keys.push_back(entry.first);
  return cmd
      ->add_option_function<std::string>(
          name, [&target, names](const std::string& s) { target = names.at(s); }, help)
      ->check(CLI::IsMember(keys));
}

/// Input flags (--columns, --classes, --drop-classes, --crop, --voxel, --max-points) bound to `read`, which must
/// outlive the parse.
void add_read_options(CLI::App* cmd, io::ReadOptions& read);

/// One line for --timings and info: what cropping, class filters and thinning left of the file's points.
std::string describe_reduction(const io::ReadResult& read);

/// Surface analysis flags (--neighbours, --recompute-normals, --orientation, --outward) bound to `surface`, which
/// must outlive the parse.
void add_surface_options(CLI::App* cmd, differential::SurfaceOptions& surface);

/// Ridge/valley flags of the paper's §IV.A (detection, tracing, joining) bound to `options`, which must outlive the
/// parse.
void add_ridge_valley_options(CLI::App* cmd, features::RidgeValleyOptions& options);

/// Every flag of `draw` that sets a DrawOptions field but --max-memory (camera, surface analysis, ridges and valleys,
/// contours and visibility, thickness, shadows, output), bound to `options`, which must outlive the parse. The
/// Python module registers the same flags to read its keyword arguments.
void add_draw_options(CLI::App* cmd, DrawOptions& options);

/// Page flags (--scale, --units, --scale-bar, --north-arrow) bound to `page`, which must outlive the parse.
void add_page_options(CLI::App* cmd, page::PageOptions& page);

/// --max-memory GB bound to `target` (draw, features), which must outlive the parse.
void add_memory_option(CLI::App* cmd, std::optional<double>& target);

/// One file, however it is spelled (a/../b.svg, ./b.svg, a symlink to it): for the "written twice" checks.
std::filesystem::path same_file_key(const std::string& path);

/// check_writable(path) before any work, its failure an OptionError naming `flag` (exit 1).
void check_output_path(const std::string& flag, const std::string& path);

}  // namespace pcsketch::cli
