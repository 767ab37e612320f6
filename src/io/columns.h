#pragma once
// What the columns of a text file hold: --columns lists, header names, and the guess from the values when neither
// is given (so that `x y z r g b` is never read as normals).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/io/read_cloud.h"

namespace pcsketch::io::detail {

/// A normal counts as unit length when | |n| - 1 | is at most this: six printed decimals, float rounding and
/// renormalised-then-quantised exports all pass; colours and unnormalised vectors do not.
inline constexpr float kUnitTolerance = 0.02f;
/// Normals are taken as normals when at least this fraction of them is unit length.
inline constexpr double kUnitShare = 0.99;

/// The fraction of `normals` that are unit length (1 for none).
double unit_fraction(std::span<const Vec3f> normals);

/// The column a header name stands for (quotes, a leading "//" or "#" and case ignored; X/Easting, Y/Northing,
/// Z/Elevation/Height, nx/normal_x, r/red, i/intensity…); nullopt for a name it does not know.
std::optional<Column> column_from_name(std::string_view name);

/// The name of `c` as --columns spells it.
std::string_view column_name(Column c);

/// A header row: the columns its names give (unknown names are Skip), or nullopt unless it names x, y and z.
std::optional<std::vector<Column>> columns_from_header(std::span<const std::string_view> names);

/// What the layout guess and the colour scale need from the values of a text file, gathered row by row (one pass of
/// a streamed read, no table).
struct ColumnStats {
  explicit ColumnStats(std::size_t columns)
      : width(columns), bytes(columns, 1), unit_range(columns, 1), whole(columns, 1) {}
  /// Adds one row of `width` values.
  void add(const float* row);

  std::size_t width;
  std::uint64_t rows = 0;
  /// Per column, 1 while every value is an integer in 0-255 / lies in [0, 1] / is whole.
  std::vector<std::uint8_t> bytes, unit_range, whole;
  /// Rows whose three columns from 3 + first are a unit vector (kUnitTolerance), for first = 0, 1 and 3.
  std::array<std::uint64_t, 3> unit{};
};

/// The columns of a file without --columns or header, from the statistics of its first `stats.width` columns: x y
/// z, then for `.pts` intensity [r g b]; otherwise each group of three after x y z (columns 4-6, 7-9; or 5-7 after an
/// intensity in 7-column files) is normals if unit length at kUnitShare of the rows, colour if every value is an
/// integer in 0-255 or lies in [0, 1], else skipped with a warning saying so and how to override it.
/// @return `stats.width` columns
std::vector<Column> guess_columns(const ColumnStats& stats, bool pts, const std::string& path, Warnings& warnings);

/// "x,y,z,r,g,b": a layout as --columns would spell it.
std::string columns_to_string(std::span<const Column> columns);

}  // namespace pcsketch::io::detail
