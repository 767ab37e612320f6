// XYZ / PTS / TXT / CSV / ASC reader: one point per line, columns separated by blanks, commas or semicolons.

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "columns.h"
#include "core/progress.h"
#include "raw_cloud.h"
#include "text_scan.h"

namespace pcsketch::io::detail {
namespace {

/// Columns read when guessing the layout: x y z and two groups of three (normals, colours).
constexpr std::size_t kGuessWidth = 9;

bool is_comment_or_blank(std::string_view line) {
  // Separators alone (e.g. ",,," in a spreadsheet export) make a blank line too.
  const std::size_t i = line.find_first_not_of(" \t\r\v\f,;");
  return i == std::string_view::npos || line[i] == '#' || line.substr(i).starts_with("//");
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  Tokens tokens(line, true);
  std::string_view t;
  while (tokens.next(t)) out.push_back(t);
  return out;
}

// The layout as read: what each column holds, and the names of a header row (for the columns not kept).
struct Layout {
  std::vector<Column> columns;  ///< empty until known
  std::vector<std::string> names;
  std::string how;  ///< "--columns", "header" or "guessed from the values"
};

// A header row (CloudCompare's "//X,Y,Z,R,G,B", a CSV's "X","Y","Z" first line, "# x y z nx ny nz"): true if it
// names x, y and z.
bool read_header(std::string_view line, Layout& layout) {
  const std::vector<std::string_view> names = split(line);
  const std::optional<std::vector<Column>> columns = columns_from_header(names);
  if (!columns) return false;
  layout.columns = *columns;
  layout.names.assign(names.begin(), names.end());
  layout.how = "header";
  return true;
}

float column_value(const std::vector<float>& table, std::size_t width, std::size_t row, std::size_t column) {
  return table[row * width + column];
}

// Normals, colours and intensity from the columns that hold them; the rest is listed as not kept.
void gather(RawCloud& raw, const Layout& layout, const std::vector<float>& table, std::size_t width) {
  const auto find = [&](Column c) {
    const auto it = std::find(layout.columns.begin(), layout.columns.end(), c);
    return it == layout.columns.end() ? width : static_cast<std::size_t>(it - layout.columns.begin());
  };
  const std::size_t rows = raw.positions.size();
  const std::array<std::size_t, 3> n{find(Column::Nx), find(Column::Ny), find(Column::Nz)};
  const std::array<std::size_t, 3> rgb{find(Column::Red), find(Column::Green), find(Column::Blue)};
  const bool has_normals = n[0] < width && n[1] < width && n[2] < width;
  const bool has_colors = rgb[0] < width && rgb[1] < width && rgb[2] < width;
  if (has_normals)
    for (std::size_t r = 0; r < rows; ++r)
      raw.normals.emplace_back(column_value(table, width, r, n[0]), column_value(table, width, r, n[1]),
                               column_value(table, width, r, n[2]));
  if (has_colors) {
    // Colours in [0, 1] with a fraction somewhere are scaled to 0-255; whole numbers are taken as 0-255.
    bool unit_range = true, whole = true;
    for (std::size_t r = 0; r < rows; ++r)
      for (const std::size_t c : rgb) {
        const float v = column_value(table, width, r, c);
        unit_range = unit_range && v >= 0.f && v <= 1.f;
        whole = whole && v == std::floor(v);
      }
    const double scale = unit_range && !whole ? 255.0 : 1.0;
    for (std::size_t r = 0; r < rows; ++r)
      raw.colors.push_back({to_channel(scale * column_value(table, width, r, rgb[0])),
                            to_channel(scale * column_value(table, width, r, rgb[1])),
                            to_channel(scale * column_value(table, width, r, rgb[2]))});
  }
  for (std::size_t c = 0; c < width; ++c) {
    const Column kind = layout.columns[c];
    if (kind == Column::Intensity) {
      PointAttribute& a = raw.attributes.emplace_back(PointAttribute{"intensity", {}});
      for (std::size_t r = 0; r < rows; ++r) a.values.push_back(column_value(table, width, r, c));
      continue;
    }
    const bool kept = kind == Column::X || kind == Column::Y || kind == Column::Z ||
                      (has_normals && (kind == Column::Nx || kind == Column::Ny || kind == Column::Nz)) ||
                      (has_colors && (kind == Column::Red || kind == Column::Green || kind == Column::Blue));
    if (!kept)
      raw.other_attributes.push_back(c < layout.names.size() ? layout.names[c] : "column " + std::to_string(c + 1));
  }
}

// The columns read from each line, fixed by the first data line: the layout's, or up to kGuessWidth to guess from.
// `xyz` gets the columns of x, y and z.
std::size_t table_width(std::string_view line, const Layout& layout, const Source& src, std::uint64_t line_number,
                        std::vector<std::string>& not_kept, std::array<std::size_t, 3>& xyz) {
  if (!layout.columns.empty()) {
    for (std::size_t s = 0; s < 3; ++s)
      xyz[s] = static_cast<std::size_t>(
          std::find(layout.columns.begin(), layout.columns.end(), static_cast<Column>(s)) - layout.columns.begin());
    return layout.columns.size();
  }
  const std::size_t line_width = split(line).size();
  if (line_width < 3)
    src.fail_at_line(line_number, "XYZ: too few columns (" + std::to_string(line_width) + "; need x y z)");
  for (std::size_t c = kGuessWidth; c < line_width; ++c) not_kept.push_back("column " + std::to_string(c + 1));
  return std::min(line_width, kGuessWidth);
}

}  // namespace

RawCloud parse_xyz(const Source& src, Want) {
  std::string ext = std::filesystem::path(src.path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) { return static_cast<char>(std::tolower(c)); });
  RawCloud raw;
  raw.format = ext.size() > 1 ? ext.substr(1) : "xyz";

  Layout layout{{src.columns.begin(), src.columns.end()}, {}, src.columns.empty() ? "" : "--columns"};
  LineReader lines(skip_bom(src.bytes), 1, src.path);
  std::string_view line;
  bool first_data_line = true;
  std::size_t width = 0;  // columns read from each line
  std::size_t line_columns = 0;  // columns every line has: those of the first data line
  std::array<std::size_t, 3> xyz{0, 1, 2};
  std::vector<float> table;  // #P by width: every column read, as float (positions are kept in double apart)
  static const ProgressFn kNone;
  pcsketch::detail::ProgressSteps steps(src.progress ? *src.progress : kNone, "read", src.bytes.size());
  while (lines.next(line)) {
    steps.at(lines.consumed(src.bytes));
    if (is_comment_or_blank(line)) {
      // A header may hide in a comment: CloudCompare writes "//X,Y,Z,R,G,B".
      if (first_data_line && layout.columns.empty()) {
        const std::size_t start = line.find_first_not_of(" \t#/");
        if (start != std::string_view::npos) read_header(line.substr(start), layout);
      }
      continue;
    }
    if (first_data_line) {
      first_data_line = false;
      const std::vector<std::string_view> tokens = split(line);
      double unused = 0;
      std::uint64_t count = 0;
      if (tokens.size() == 1 && parse_uint(tokens[0], count)) continue;  // the PTS count line: a hint only
      if (!parse_double(tokens[0], unused)) {
        // With --columns, a header row is skipped; without, it must name x, y and z.
        if (!src.columns.empty()) continue;
        if (!read_header(line, layout))
          src.fail_at_line(lines.line(), "XYZ: non-numeric first line is not a header naming x, y and z columns");
        continue;
      }
    }
    if (width == 0) {
      width = table_width(line, layout, src, lines.line(), raw.other_attributes, xyz);
      line_columns = split(line).size();
    }
    // Column c of this line: a position in double, anything else into the table as float.
    Tokens tokens(line, true);
    std::string_view token;
    Vec3d p = Vec3d::Zero();
    for (std::size_t c = 0; c < width; ++c) {
      if (!tokens.next(token))
        src.fail_at_line(lines.line(),
                         "XYZ: " + std::to_string(c) + " columns where the first line has " +
                             std::to_string(line_columns));
      double v = 0;
      if (!layout.columns.empty() && layout.columns[c] == Column::Skip) {
        table.push_back(0.f);
        continue;
      }
      if (!parse_double(token, v))
        src.fail_at_line(lines.line(), "XYZ: " + bad_number(token) + " in column " + std::to_string(c + 1));
      table.push_back(static_cast<float>(v));
      for (std::size_t s = 0; s < 3; ++s)
        if (xyz[s] == c) p[static_cast<Eigen::Index>(s)] = v;
    }
    // A row with a column more or less than the first would shift or misread values.
    std::size_t count = width;
    while (tokens.next(token)) ++count;
    if (count != line_columns)
      src.fail_at_line(lines.line(), "XYZ: " + std::to_string(count) + " columns where the first line has " +
                                         std::to_string(line_columns));
    raw.positions.push_back(p);
  }
  if (width == 0) return raw;
  if (layout.columns.empty()) {
    layout.columns = guess_columns(table, width, raw.format == "pts", src.path, raw.warnings);
    layout.how = raw.format == "pts" ? "the PTS convention" : "guessed from the values";
  }
  gather(raw, layout, table, width);
  raw.columns = columns_to_string(layout.columns) + " (" + layout.how + ")";
  return raw;
}

}  // namespace pcsketch::io::detail
