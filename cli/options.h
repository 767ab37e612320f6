#pragma once
// Flag blocks shared by several subcommands. The option flags come from the option table (pcsketch/options_table.h),
// so `features`, `draw` and the Python module accept the same names, checks and defaults in the same words; the
// input flags and the few options a table entry cannot parse (--file-normals, --max-memory) are written here.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "pcsketch/io/read_cloud.h"
#include "pcsketch/options_table.h"
#include "pcsketch/pipeline.h"

namespace pcsketch::cli {

/// Input flags (--columns, --classes, --drop-classes, --crop, --voxel, --max-points, --full-resolution) bound to
/// `read`, which must outlive the parse. Thinning to the output's resolution is on (for a 1024 x 1024 image until
/// for_image() says otherwise).
void add_read_options(CLI::App* cmd, io::ReadOptions& read);

/// The image `read` is thinned for by default (io::OutputResolution): the size and projection of `camera`; none for a
/// perspective eye placed by hand. Nothing when --full-resolution took the resolution rule off.
void for_image(io::ReadOptions& read, const view::CameraOptions& camera);

/// Bytes a point costs while read whole (double positions 24, normals 12, colours 3, float positions 12, rounded
/// up: docs/geometry.md "Memory per point"), beyond what the analysis needs.
inline constexpr double kReadBytesPerPoint = 64;

/// Memory available to a new allocation: MemAvailable of /proc/meminfo (PCSKETCH_MEM_AVAILABLE, in bytes, replaces
/// it for tests).
double available_memory_bytes();

/// With --full-resolution (no thinning at all), refuses before reading a file whose header count (PLY) times
/// kReadBytesPerPoint + `bytes_per_point` exceeds available_memory_bytes(). @throws OptionError (exit 1).
void check_full_resolution(const io::ReadOptions& read, const std::string& input, double bytes_per_point);

/// What the read kept, for the JSON output ("input": points in the file, dropped, kept, the thinning's cell and
/// reason); null when nothing was thinned, so that the JSON of an untouched cloud is unchanged.
nlohmann::json input_json(const io::ReadResult& read);

/// One line for --timings and info: what cropping, class filters and thinning left of the file's points.
std::string describe_reduction(const io::ReadResult& read);

/// The flags of the option table (pcsketch/options_table.h) bound from the table, for the entries `wanted` accepts,
/// bound to `options`, which must outlive the parse. Each value is range-checked while parsing.
void add_table_flags(CLI::App* cmd, DrawOptions& options, const std::function<bool(const options::Option&)>& wanted);

/// Surface analysis and ridge/valley flags (the `surface.` and `features.` options, --file-normals) bound to
/// `options`, which must outlive the parse: the flags `features` and `draw` share.
void add_analysis_flags(CLI::App* cmd, DrawOptions& options);

/// Every flag of `draw` that sets a DrawOptions field but --max-memory (camera, surface analysis, ridges and valleys,
/// contours and visibility, thickness, shadows, output), bound to `options`, which must outlive the parse. The
/// Python module registers the same flags to read its keyword arguments.
void add_draw_options(CLI::App* cmd, DrawOptions& options);

/// --scale (a ratio such as 1:20, which the option table cannot bind) bound to `page`, which must outlive the parse.
void add_scale_option(CLI::App* cmd, page::PageOptions& page);

/// --max-memory GB bound to `target` (draw, features), which must outlive the parse.
void add_memory_option(CLI::App* cmd, std::optional<double>& target);

/// One file, however it is spelled (a/../b.svg, ./b.svg, a symlink to it): for the "written twice" checks.
std::filesystem::path same_file_key(const std::string& path);

/// check_writable(path) before any work, its failure an OptionError naming `flag` (exit 1).
void check_output_path(const std::string& flag, const std::string& path);

}  // namespace pcsketch::cli
