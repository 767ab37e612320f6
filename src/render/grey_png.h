#pragma once
// A minimal PNG encoder for 8-bit grey images (private to the render stage).

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace pcsketch::render::detail {

/// Writes `height` rows of `width` grey bytes (row r at pixels + r·stride) as an 8-bit greyscale PNG with a white
/// bKGD, rows unfiltered and deflated at zlib's fastest level: line drawings are mostly blank, so this is within
/// ~10% of the size of adaptive filtering at the default level, at about a fifth of the time.
/// @throws pcsketch::Error naming `path` if the file cannot be written
void write_grey_png(const std::uint8_t* pixels, int width, int height, std::ptrdiff_t stride,
                    const std::filesystem::path& path);

}  // namespace pcsketch::render::detail
