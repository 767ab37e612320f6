// Column layouts of text files: parsing --columns, reading header names, guessing from the values.

#include "columns.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "pcsketch/core/error.h"

namespace pcsketch::io {
namespace {

struct Name {
  std::string_view name;
  Column column;
};

// The first name of each column is the one --columns prints; the others are what exports call it.
constexpr std::array kNames{
    Name{"x", Column::X},        Name{"easting", Column::X},   Name{"east", Column::X},
    Name{"y", Column::Y},        Name{"northing", Column::Y},  Name{"north", Column::Y},
    Name{"z", Column::Z},        Name{"elevation", Column::Z}, Name{"height", Column::Z},
    Name{"altitude", Column::Z}, Name{"nx", Column::Nx},       Name{"normal_x", Column::Nx},
    Name{"normalx", Column::Nx}, Name{"ny", Column::Ny},       Name{"normal_y", Column::Ny},
    Name{"normaly", Column::Ny}, Name{"nz", Column::Nz},       Name{"normal_z", Column::Nz},
    Name{"normalz", Column::Nz}, Name{"r", Column::Red},       Name{"red", Column::Red},
    Name{"g", Column::Green},    Name{"green", Column::Green}, Name{"b", Column::Blue},
    Name{"blue", Column::Blue},  Name{"i", Column::Intensity}, Name{"intensity", Column::Intensity},
    Name{"skip", Column::Skip},
};

std::string lower_unquoted(std::string_view name) {
  if (name.starts_with("//")) name.remove_prefix(2);
  if (name.starts_with("#")) name.remove_prefix(1);
  if (name.size() >= 2 && (name.front() == '"' || name.front() == '\'') && name.back() == name.front())
    name = name.substr(1, name.size() - 2);
  std::string out(name);
  std::transform(out.begin(), out.end(), out.begin(), [](char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool has_xyz(std::span<const Column> columns) {
  for (const Column c : {Column::X, Column::Y, Column::Z})
    if (std::count(columns.begin(), columns.end(), c) != 1) return false;
  return true;
}

}  // namespace

std::vector<Column> parse_columns(std::string_view spec) {
  std::vector<Column> columns;
  while (!spec.empty()) {
    const std::size_t comma = spec.find(',');
    const std::string_view name = spec.substr(0, comma);
    spec = comma == std::string_view::npos ? std::string_view() : spec.substr(comma + 1);
    const std::optional<Column> c = detail::column_from_name(name);
    if (!c)
      throw Error("unknown column \"" + std::string(name.substr(0, 32)) +
                  "\" in the column list (use x y z r g b i nx ny nz skip)");
    if (*c != Column::Skip && std::find(columns.begin(), columns.end(), *c) != columns.end())
      throw Error("column \"" + std::string(name.substr(0, 32)) + "\" is named twice in the column list");
    columns.push_back(*c);
  }
  if (!has_xyz(columns)) throw Error("the column list must include x, y and z");
  return columns;
}

namespace detail {

double unit_fraction(std::span<const Vec3f> normals) {
  if (normals.empty()) return 1.0;
  const auto unit = std::count_if(normals.begin(), normals.end(),
                                  [](const Vec3f& n) { return std::abs(n.norm() - 1.f) <= kUnitTolerance; });
  return static_cast<double>(unit) / static_cast<double>(normals.size());
}

std::optional<Column> column_from_name(std::string_view name) {
  const std::string lower = lower_unquoted(name);
  for (const Name& n : kNames)
    if (n.name == lower) return n.column;
  return std::nullopt;
}

std::string_view column_name(Column c) {
  for (const Name& n : kNames)
    if (n.column == c) return n.name;
  return "skip";
}

std::optional<std::vector<Column>> columns_from_header(std::span<const std::string_view> names) {
  std::vector<Column> columns;
  for (const std::string_view name : names) {
    const std::optional<Column> c = column_from_name(name);
    // A name given twice (two "intensity" fields) keeps its first column.
    const bool repeated = c && std::find(columns.begin(), columns.end(), *c) != columns.end();
    columns.push_back(c && !repeated ? *c : Column::Skip);
  }
  if (!has_xyz(columns)) return std::nullopt;
  return columns;
}

std::string columns_to_string(std::span<const Column> columns) {
  std::string out;
  for (const Column c : columns) out += (out.empty() ? "" : ",") + std::string(column_name(c));
  return out;
}

namespace {

enum class Group : std::uint8_t { Normals, Colours, Neither };

// The three unit-vector counts of ColumnStats::unit: groups from 3 + 0, 3 + 1 and 3 + 3.
constexpr std::array<std::size_t, 3> kUnitGroups{0, 1, 3};

// What the three columns from `first` (0-based after x y z) of every row hold.
Group classify(const ColumnStats& stats, std::size_t first, double& unit_share) {
  const std::size_t g =
      static_cast<std::size_t>(std::find(kUnitGroups.begin(), kUnitGroups.end(), first) - kUnitGroups.begin());
  bool bytes = true, unit_range = true;
  for (std::size_t c = 3 + first; c < 6 + first; ++c) {
    bytes = bytes && stats.bytes[c];
    unit_range = unit_range && stats.unit_range[c];
  }
  const std::uint64_t rows = stats.rows;
  unit_share = rows == 0 ? 0.0 : static_cast<double>(stats.unit[g]) / static_cast<double>(rows);
  // Unit vectors first: axis-aligned normals (0 0 1) are small integers too.
  if (rows > 0 && unit_share >= kUnitShare) return Group::Normals;
  if (bytes || unit_range) return Group::Colours;
  return Group::Neither;
}

std::string share_text(double share) { return std::to_string(static_cast<int>(std::floor(share * 100.0))) + "%"; }

}  // namespace

void ColumnStats::add(const float* row) {
  ++rows;
  for (std::size_t c = 0; c < width; ++c) {
    const float x = row[c];
    const bool integer = x == std::floor(x);
    bytes[c] = bytes[c] && x >= 0.f && x <= 255.f && integer;
    unit_range[c] = unit_range[c] && x >= 0.f && x <= 1.f;
    whole[c] = whole[c] && integer;
  }
  for (std::size_t g = 0; g < kUnitGroups.size(); ++g) {
    const std::size_t first = 3 + kUnitGroups[g];
    if (first + 3 <= width &&
        std::abs(Vec3f(row[first], row[first + 1], row[first + 2]).norm() - 1.f) <= kUnitTolerance)
      ++unit[g];
  }
}

std::vector<Column> guess_columns(const ColumnStats& stats, bool pts, const std::string& path, Warnings& warnings) {
  const std::size_t width = stats.width;
  std::vector<Column> columns(std::max<std::size_t>(width, 3), Column::Skip);
  for (std::size_t c = 0; c < 3; ++c) columns[c] = static_cast<Column>(c);
  const auto set_group = [&](std::size_t first, Column a, Column b, Column c) {
    columns[first + 3] = a;
    columns[first + 4] = b;
    columns[first + 5] = c;
  };
  if (pts) {  // the PTS convention: x y z intensity [r g b]
    if (width >= 4) columns[3] = Column::Intensity;
    if (width >= 7) set_group(1, Column::Red, Column::Green, Column::Blue);
    return columns;
  }
  if (width == 4) columns[3] = Column::Intensity;
  // Groups of three after x y z; a 7-column file may be x y z i r g b instead of x y z nx ny nz i.
  std::vector<std::size_t> groups;
  if (width >= 6) groups.push_back(0);
  if (width >= 9) groups.push_back(3);
  for (const std::size_t first : groups) {
    double share = 0;
    Group g = classify(stats, first, share);
    if (width == 7 && g != Group::Normals) {
      double shifted_share = 0;
      if (classify(stats, 1, shifted_share) == Group::Colours) {
        columns[3] = Column::Intensity;
        set_group(1, Column::Red, Column::Green, Column::Blue);
        continue;
      }
    }
    if (g == Group::Normals) set_group(first, Column::Nx, Column::Ny, Column::Nz);
    if (g == Group::Colours) set_group(first, Column::Red, Column::Green, Column::Blue);
    if (g != Group::Neither) continue;
    const std::string cols = std::to_string(first + 4) + "-" + std::to_string(first + 6);
    warnings.push_back(path + ": columns " + cols + " ignored: they are not normals (only " + share_text(share) +
                       " of the rows are unit vectors) nor colours (integers 0-255 or values in 0-1); name the "
                       "columns with a header row or --columns, e.g. --columns x,y,z,nx,ny,nz");
  }
  return columns;
}

}  // namespace detail
}  // namespace pcsketch::io
