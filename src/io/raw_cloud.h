#pragma once
// What every format reader produces before the common finishing step (drop non-finite points, recentre).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pcsketch/core/error.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io::detail {

/// The bytes of one input and the name that stands for it in messages.
struct Source {
  std::string_view bytes;
  const std::string& path;
  std::span<const Column> columns = {};  ///< text formats: ReadOptions::columns
  const ProgressFn* progress = nullptr;   ///< ReadOptions::progress, for readers whose parse takes long
  bool mapped = false;                    ///< `bytes` is a file mapping whose read pages may be released

  [[noreturn]] void fail_at_byte(std::size_t offset, const std::string& message) const {
    throw Error(FileLoc{path, {}, offset}, message);
  }
  [[noreturn]] void fail_at_line(std::uint64_t line, const std::string& message) const {
    throw Error(FileLoc{path, line, {}}, message);
  }
  [[noreturn]] void fail(const std::string& message) const { throw Error(FileLoc{path, {}, {}}, message); }
};

/// Coordinates in double as read from the file, before recentring.
struct RawCloud {
  std::vector<Vec3d> positions;
  std::vector<Vec3f> normals;                       ///< empty or #P
  std::vector<Rgb8> colors;                         ///< empty or #P
  std::vector<PointAttribute> attributes;           ///< each #P
  std::vector<std::array<std::uint32_t, 3>> faces;  ///< filled only when a mesh is asked for
  std::vector<std::string> other_attributes;
  std::string format;
  std::string columns;  ///< text formats: the column layout and how it was found
  Warnings warnings;  ///< what the reader assumed (a guessed column layout)
};

/// What a reader is asked for: the points only, or the faces too.
enum class Want : std::uint8_t { Points, Mesh };

/// Format readers: one per file, all throwing pcsketch::Error with the place of the problem.
RawCloud parse_ply(const Source& source, Want want);
RawCloud parse_xyz(const Source& source, Want want);
RawCloud parse_pcd(const Source& source, Want want);
RawCloud parse_off(const Source& source, Want want);
RawCloud parse_obj(const Source& source, Want want);
RawCloud parse_las(const Source& source, Want want);

/// PCD's magic: '#' comment lines, then a VERSION or FIELDS line.
bool sniff_pcd(std::string_view head);

/// Removes every exact copy of an earlier point (keeping the first, with its normal and colour), in expected linear
/// time; returns the number removed. Positions must be finite.
std::size_t collapse_duplicates(RawCloud& raw);

/// A colour channel from a number in [0, 255] (rounded, clamped; non-finite gives 0).
inline std::uint8_t to_channel(double v) {
  return static_cast<std::uint8_t>(std::clamp(std::round(std::isfinite(v) ? v : 0.0), 0.0, 255.0));
}

/// What left no point, for the message "none of the N points is left by the …".
inline const char* filters_named(bool by_class, bool crop) {
  return !crop ? "class filters" : by_class ? "class filters and the crop box" : "crop box";
}

/// --classes and --drop-classes: whether a point of class `c` is kept.
inline bool class_kept(const ReadOptions& options, int c) {
  const auto listed = [c](const std::vector<int>& classes) {
    return std::find(classes.begin(), classes.end(), c) != classes.end();
  };
  return (options.classes.empty() || listed(options.classes)) && !listed(options.drop_classes);
}

/// The origin of a cloud whose bounding box is [lo, hi] (docs/io.md, "Precision"): 0 unless it lies far away.
Vec3d choose_origin(const Vec3d& lo, const Vec3d& hi, const ReadOptions& options);

/// Appends the triangles of a polygon as a fan around its first corner (nothing for fewer than 3 corners).
void add_fan(std::span<const std::uint32_t> polygon, std::vector<std::array<std::uint32_t, 3>>& faces);

}  // namespace pcsketch::io::detail
