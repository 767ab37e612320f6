#pragma once
// Writing PLY files (reading goes through read_cloud.h).

#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::io {

enum class PlyFormat : std::uint8_t { Ascii, BinaryLittleEndian, BinaryBigEndian };

/// An extra per-point property: #P values written as `property float|int|uchar <name>` after the cloud's own.
struct PlyAttribute {
  std::string name;
  std::variant<std::span<const float>, std::span<const std::int32_t>, std::span<const std::uint8_t>> values;
};

struct PlyWriteOptions {
  /// Binary little-endian by default: compact, exact, and what every tool reads fastest.
  PlyFormat format = PlyFormat::BinaryLittleEndian;
  /// Free-text header comments, one per entry (no newlines).
  std::vector<std::string> comments;
};

/// Writes the cloud as one "vertex" element: x y z (world coordinates origin + position: `double` when the origin
/// is non-zero so georeferenced clouds keep their precision, `float` otherwise), then nx ny nz (float) and
/// red green blue (uchar) when present, then `attributes` in order. The file is written under a temporary name next
/// to `path` and renamed over it when complete (core/atomic_file.h): a failure leaves an existing file as it was.
/// @throws pcsketch::Error if an attribute's size is not #P, a name is empty or has spaces, or the file cannot be
///         written.
void write_ply(const std::string& path, const PointCloud& cloud, const std::vector<PlyAttribute>& attributes = {},
               const PlyWriteOptions& options = {});

}  // namespace pcsketch::io
