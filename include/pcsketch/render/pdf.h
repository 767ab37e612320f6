#pragma once
// PDF output through cairo (vector, same layers' content and paint order as the SVG, without layer structure).

#include <filesystem>

#include "pcsketch/core/drawing.h"
#include "pcsketch/render/options.h"

namespace pcsketch::render {

/// One page of width × height CSS pixels (0.75 pt each) or RenderOptions::page_width_mm wide. The document's
/// creation and modification dates are SOURCE_DATE_EPOCH (environment, seconds) when set, else 1970-01-01, never the
/// clock: the same drawing gives the same bytes.
/// @throws pcsketch::Error if cairo cannot write `path`.
void write_pdf(const Drawing& drawing, const std::filesystem::path& path, const RenderOptions& options = {});

}  // namespace pcsketch::render
