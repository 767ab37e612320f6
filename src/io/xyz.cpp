// XYZ / PTS / TXT / CSV / ASC reader: one point per line, columns separated by blanks, commas or semicolons.

#include "xyz.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/progress.h"

namespace pcsketch::io::detail {
namespace {

/// Columns read when guessing the layout: x y z and two groups of three (normals, colours).
constexpr std::size_t kGuessWidth = 9;

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  Tokens tokens(line, true);
  std::string_view t;
  while (tokens.next(t)) out.push_back(t);
  return out;
}

// A header row (CloudCompare's "//X,Y,Z,R,G,B", a CSV's "X","Y","Z" first line, "# x y z nx ny nz"): true if it
// names x, y and z.
bool read_header(std::string_view line, XyzLayout& layout) {
  const std::vector<std::string_view> names = split(line);
  const std::optional<std::vector<Column>> columns = columns_from_header(names);
  if (!columns) return false;
  layout.columns = *columns;
  layout.names.assign(names.begin(), names.end());
  layout.how = "header";
  return true;
}

}  // namespace

bool is_comment_or_blank(std::string_view line) {
  // Separators alone (e.g. ",,," in a spreadsheet export) make a blank line too.
  const std::size_t i = line.find_first_not_of(" \t\r\v\f,;");
  return i == std::string_view::npos || line[i] == '#' || line.substr(i).starts_with("//");
}

std::string xyz_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) { return static_cast<char>(std::tolower(c)); });
  return ext.size() > 1 ? ext.substr(1) : "xyz";
}

XyzRows::XyzRows(const Source& source)
    : src_(source),
      layout_{{source.columns.begin(), source.columns.end()}, {}, source.columns.empty() ? "" : "--columns"},
      lines_(skip_bom(source.bytes), 1, source.path) {}

// Whether `line` holds a row; a comment may hide a header (CloudCompare writes "//X,Y,Z,R,G,B").
bool XyzRows::data_line(std::string_view line) {
  if (is_comment_or_blank(line)) {
    if (first_data_line_ && layout_.columns.empty()) {
      const std::size_t start = line.find_first_not_of(" \t#/");
      if (start != std::string_view::npos) read_header(line.substr(start), layout_);
    }
    return false;
  }
  if (!first_data_line_) return true;
  first_data_line_ = false;
  const std::vector<std::string_view> tokens = split(line);
  double unused = 0;
  std::uint64_t count = 0;
  if (tokens.size() == 1 && parse_uint(tokens[0], count)) return false;  // the PTS count line: a hint only
  if (parse_double(tokens[0], unused)) return true;
  // With --columns, a header row is skipped; without, it must name x, y and z.
  if (src_.columns.empty() && !read_header(line, layout_))
    src_.fail_at_line(lines_.line(), "XYZ: non-numeric first line is not a header naming x, y and z columns");
  return false;
}

// The columns read from each row, fixed by the first: the layout's, or up to kGuessWidth to guess from.
void XyzRows::first_row(std::string_view line) {
  line_columns_ = split(line).size();
  if (!layout_.columns.empty()) {
    for (std::size_t s = 0; s < 3; ++s)
      xyz_[s] = static_cast<std::size_t>(
          std::find(layout_.columns.begin(), layout_.columns.end(), static_cast<Column>(s)) - layout_.columns.begin());
    row_.resize(layout_.columns.size());
    return;
  }
  if (line_columns_ < 3)
    src_.fail_at_line(lines_.line(), "XYZ: too few columns (" + std::to_string(line_columns_) + "; need x y z)");
  for (std::size_t c = kGuessWidth; c < line_columns_; ++c) unread_.push_back("column " + std::to_string(c + 1));
  row_.resize(std::min(line_columns_, kGuessWidth));
}

bool XyzRows::next(Vec3d& p) {
  std::string_view line;
  do {
    if (!lines_.next(line)) return false;
  } while (!data_line(line));
  if (row_.empty()) first_row(line);
  // Column c of this line: a position in double, anything else as float.
  Tokens tokens(line, true);
  std::string_view token;
  p = Vec3d::Zero();
  const std::size_t width = row_.size();
  for (std::size_t c = 0; c < width; ++c) {
    if (!tokens.next(token))
      src_.fail_at_line(lines_.line(), "XYZ: " + std::to_string(c) + " columns where the first line has " +
                                           std::to_string(line_columns_));
    row_[c] = 0.f;
    if (!layout_.columns.empty() && layout_.columns[c] == Column::Skip) continue;
    double v = 0;
    if (!parse_double(token, v))
      src_.fail_at_line(lines_.line(), "XYZ: " + bad_number(token) + " in column " + std::to_string(c + 1));
    row_[c] = static_cast<float>(v);
    for (std::size_t s = 0; s < 3; ++s)
      if (xyz_[s] == c) p[static_cast<Eigen::Index>(s)] = v;
  }
  // A row with a column more or less than the first would shift or misread values.
  std::size_t count = width;
  while (tokens.next(token)) ++count;
  if (count != line_columns_)
    src_.fail_at_line(lines_.line(), "XYZ: " + std::to_string(count) + " columns where the first line has " +
                                         std::to_string(line_columns_));
  return true;
}

XyzFields::XyzFields(const XyzLayout& layout, std::size_t columns) : width(columns) {
  const auto find = [&](Column c) {
    const auto it = std::find(layout.columns.begin(), layout.columns.end(), c);
    return it == layout.columns.end() ? width : static_cast<std::size_t>(it - layout.columns.begin());
  };
  normal = {find(Column::Nx), find(Column::Ny), find(Column::Nz)};
  rgb = {find(Column::Red), find(Column::Green), find(Column::Blue)};
  intensity = find(Column::Intensity);
  has_normals = normal[0] < width && normal[1] < width && normal[2] < width;
  has_colors = rgb[0] < width && rgb[1] < width && rgb[2] < width;
}

std::vector<std::string> XyzFields::not_kept(const XyzLayout& layout, std::vector<std::string> out) const {
  for (std::size_t c = 0; c < width; ++c) {
    const Column kind = layout.columns[c];
    const bool kept = kind == Column::X || kind == Column::Y || kind == Column::Z || kind == Column::Intensity ||
                      (has_normals && (kind == Column::Nx || kind == Column::Ny || kind == Column::Nz)) ||
                      (has_colors && (kind == Column::Red || kind == Column::Green || kind == Column::Blue));
    if (!kept) out.push_back(c < layout.names.size() ? layout.names[c] : "column " + std::to_string(c + 1));
  }
  return out;
}

double colour_scale(const ColumnStats& stats, const XyzFields& fields) {
  if (!fields.has_colors) return 1.0;  // rgb holds no column then (width, past the statistics)
  bool unit_range = true, whole = true;
  for (const std::size_t c : fields.rgb) {
    unit_range = unit_range && stats.unit_range[c];
    whole = whole && stats.whole[c];
  }
  return unit_range && !whole ? 255.0 : 1.0;
}

std::string describe(const XyzLayout& layout) { return columns_to_string(layout.columns) + " (" + layout.how + ")"; }

void guess_layout(XyzLayout& layout, const ColumnStats& stats, const std::string& format, const std::string& path,
                  Warnings& warnings) {
  layout.columns = guess_columns(stats, format == "pts", path, warnings);
  layout.how = format == "pts" ? "the PTS convention" : "guessed from the values";
}

RawCloud parse_xyz(const Source& src, Want) {
  RawCloud raw;
  raw.format = xyz_format(src.path);
  XyzRows rows(src);
  std::vector<float> table;  // #P by width: every column read, as float (positions are kept in double apart)
  static const ProgressFn kNone;
  pcsketch::detail::ProgressSteps steps(src.progress ? *src.progress : kNone, "read", src.bytes.size());
  Vec3d p;
  while (rows.next(p)) {
    steps.at(rows.consumed());
    table.insert(table.end(), rows.row(), rows.row() + rows.width());
    raw.positions.push_back(p);
  }
  const std::size_t width = rows.width();
  if (width == 0) return raw;
  XyzLayout& layout = rows.layout();
  ColumnStats stats(width);
  for (std::size_t r = 0; r < raw.positions.size(); ++r) stats.add(table.data() + r * width);
  if (layout.columns.empty()) guess_layout(layout, stats, raw.format, src.path, raw.warnings);
  const XyzFields f(layout, width);
  const auto at = [&](std::size_t r, std::size_t c) { return table[r * width + c]; };
  const std::size_t n = raw.positions.size();
  for (std::size_t r = 0; f.has_normals && r < n; ++r)
    raw.normals.emplace_back(at(r, f.normal[0]), at(r, f.normal[1]), at(r, f.normal[2]));
  const double scale = colour_scale(stats, f);
  for (std::size_t r = 0; f.has_colors && r < n; ++r)
    raw.colors.push_back({to_channel(scale * at(r, f.rgb[0])), to_channel(scale * at(r, f.rgb[1])),
                          to_channel(scale * at(r, f.rgb[2]))});
  if (f.intensity < width) {
    PointAttribute& a = raw.attributes.emplace_back(PointAttribute{"intensity", {}});
    for (std::size_t r = 0; r < n; ++r) a.values.push_back(at(r, f.intensity));
  }
  raw.other_attributes = f.not_kept(layout, rows.unread());
  raw.columns = describe(layout);
  return raw;
}

}  // namespace pcsketch::io::detail
