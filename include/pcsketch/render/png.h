#pragma once
// PNG output through cairo: anti-aliased lines on a white background.

#include <filesystem>

#include "pcsketch/core/drawing.h"
#include "pcsketch/render/options.h"

namespace pcsketch::render {

/// width × height pixels, 8-bit greyscale (every ink is a grey), white background, cairo's default anti-aliasing.
/// @throws pcsketch::Error for an image size of zero or above 32767, or if the file cannot be written.
void write_png(const Drawing& drawing, const std::filesystem::path& path, const RenderOptions& options = {});

}  // namespace pcsketch::render
