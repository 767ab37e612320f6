#pragma once
// One entry point for every output format, chosen by the file extension.

#include <filesystem>
#include <vector>

#include "pcsketch/core/drawing.h"
#include "pcsketch/core/report.h"
#include "pcsketch/render/options.h"

namespace pcsketch::render {

/// Writes `drawing` to `path` as SVG, PDF, PNG or JSON according to its extension (.svg, .pdf, .png, .json,
/// case-insensitive). The file is written next to `path` under a temporary name and renamed over it when complete
/// (over the file a symlink points to, keeping the link): a failure leaves an existing file as it was.
/// @throws pcsketch::Error for another extension or a write failure.
void write_drawing(const Drawing& drawing, const std::filesystem::path& path, const RenderOptions& options = {});

/// write_drawing() for every path, the files in parallel (each has its own cairo surface). `progress` (optional)
/// sees "writing" at 0 before the files and at 1 once all are complete, before any replaces its target: a stop asked
/// for then (pcsketch::Cancelled) leaves no file. @throws pcsketch::Error as write_drawing(), the first failure in
/// `paths` order if several fail; the other files are still written.
void write_drawings(const Drawing& drawing, const std::vector<std::filesystem::path>& paths,
                    const RenderOptions& options = {}, const ProgressFn& progress = {});

/// Checks, before any work, that write_drawing() could write `path`: a known extension, an existing writable
/// directory, and no directory, device or FIFO in its place. @throws pcsketch::Error naming the path and why.
void check_output(const std::filesystem::path& path);

/// Whether write_drawing() knows the extension of `path`.
bool is_supported_output(const std::filesystem::path& path);

}  // namespace pcsketch::render
