#pragma once
// One entry point for every output format, chosen by the file extension.

#include <filesystem>

#include "pcsketch/core/drawing.h"
#include "pcsketch/render/options.h"

namespace pcsketch::render {

/// Writes `drawing` to `path` as SVG, PDF, PNG or JSON according to its extension (.svg, .pdf, .png, .json,
/// case-insensitive). @throws pcsketch::Error for another extension or a write failure.
void write_drawing(const Drawing& drawing, const std::filesystem::path& path, const RenderOptions& options = {});

/// Whether write_drawing() knows the extension of `path`.
bool is_supported_output(const std::filesystem::path& path);

}  // namespace pcsketch::render
