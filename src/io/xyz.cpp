// XYZ / PTS / TXT / CSV / ASC reader: one point per line, columns separated by blanks, commas or semicolons.

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>

#include "io/raw_cloud.h"
#include "io/text_scan.h"

namespace pcsketch::io::detail {
namespace {

constexpr int kNone = -1;
/// Column of each slot: 0-2 position, 3-5 normal, 6-8 colour.
using Columns = std::array<int, 9>;

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

// A header line names the columns (CSV exports): x y z, nx ny nz or normal_x …, red green blue or r g b.
Columns columns_from_names(const std::vector<std::string_view>& names, std::vector<std::string>& others) {
  static constexpr std::array<std::array<std::string_view, 3>, 9> kNames{{{"x", "", ""},
                                                                          {"y", "", ""},
                                                                          {"z", "", ""},
                                                                          {"nx", "normal_x", ""},
                                                                          {"ny", "normal_y", ""},
                                                                          {"nz", "normal_z", ""},
                                                                          {"red", "r", ""},
                                                                          {"green", "g", ""},
                                                                          {"blue", "b", ""}}};
  Columns columns;
  columns.fill(kNone);
  for (std::size_t c = 0; c < names.size(); ++c) {
    std::string lower(names[c]);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](char ch) { return static_cast<char>(std::tolower(ch)); });
    bool used = false;
    for (std::size_t s = 0; s < kNames.size(); ++s)
      if (columns[s] == kNone && !lower.empty() &&
          std::find(kNames[s].begin(), kNames[s].end(), lower) != kNames[s].end()) {
        columns[s] = static_cast<int>(c);
        used = true;
      }
    if (!used) others.push_back(std::string(names[c]));
  }
  return columns;
}

// Without a header: x y z, then nx ny nz from 6 columns and red green blue from 9; PTS: x y z intensity [r g b].
Columns columns_from_count(std::size_t count, bool pts, std::vector<std::string>& others) {
  Columns columns;
  columns.fill(kNone);
  for (int s = 0; s < 3; ++s) columns[s] = s;
  std::size_t used = 3;
  if (pts && count >= 4) {
    others.push_back("intensity");
    used = 4;
    if (count >= 7) {
      for (int s = 6; s < 9; ++s) columns[s] = s - 2;
      used = 7;
    }
  } else {
    if (count >= 6) {
      for (int s = 3; s < 6; ++s) columns[s] = s;
      used = 6;
    }
    if (count >= 9) {
      for (int s = 6; s < 9; ++s) columns[s] = s;
      used = 9;
    }
  }
  for (std::size_t c = used; c < count; ++c) others.push_back("column " + std::to_string(c + 1));
  return columns;
}

}  // namespace

RawCloud parse_xyz(const Source& src, Want) {
  std::string ext = std::filesystem::path(src.path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) { return static_cast<char>(std::tolower(c)); });
  RawCloud raw;
  raw.format = ext.size() > 1 ? ext.substr(1) : "xyz";

  LineReader lines(skip_bom(src.bytes), 1, src.path);
  std::string_view line;
  std::optional<Columns> columns;
  bool first_data_line = true;
  int needed = 0;         // columns read from each line
  std::size_t width = 0;  // columns every line has: those of the first (header or data)
  std::vector<int> slot_of_column;
  bool has_normals = false, has_colors = false;
  std::array<double, 9> v{};
  while (lines.next(line)) {
    if (is_comment_or_blank(line)) continue;
    if (first_data_line) {
      first_data_line = false;
      const std::vector<std::string_view> tokens = split(line);
      double unused = 0;
      std::uint64_t count = 0;
      if (tokens.size() == 1 && parse_uint(tokens[0], count)) continue;  // the PTS count line: a hint only
      if (!parse_double(tokens[0], unused)) {
        width = tokens.size();
        columns = columns_from_names(tokens, raw.other_attributes);
        if ((*columns)[0] == kNone || (*columns)[1] == kNone || (*columns)[2] == kNone)
          src.fail_at_line(lines.line(), "XYZ: non-numeric first line is not a header naming x, y and z columns");
        continue;
      }
    }
    if (!columns) {
      const std::size_t count = split(line).size();
      if (count < 3) src.fail_at_line(lines.line(), "XYZ: too few columns (" + std::to_string(count) + "; need x y z)");
      columns = columns_from_count(count, raw.format == "pts", raw.other_attributes);
      width = count;
    }
    if (needed == 0) {
      has_normals = (*columns)[3] != kNone && (*columns)[4] != kNone && (*columns)[5] != kNone;
      has_colors = (*columns)[6] != kNone && (*columns)[7] != kNone && (*columns)[8] != kNone;
      for (int s = 0; s < 9; ++s)
        if (s < 3 || (s < 6 ? has_normals : has_colors)) needed = std::max(needed, (*columns)[s] + 1);
      slot_of_column.assign(needed, kNone);
      for (int s = 0; s < 9; ++s)
        if ((*columns)[s] != kNone && (*columns)[s] < needed) slot_of_column[(*columns)[s]] = s;
    }
    // Column c of this line goes to the slot that reads it.
    Tokens tokens(line, true);
    std::string_view token;
    for (int c = 0; c < needed; ++c) {
      if (!tokens.next(token))
        src.fail_at_line(lines.line(),
                         "XYZ: too few columns (" + std::to_string(c) + "; need " + std::to_string(needed) + ")");
      if (slot_of_column[c] == kNone) continue;
      if (!parse_double(token, v[slot_of_column[c]]))
        src.fail_at_line(lines.line(), "XYZ: " + bad_number(token) + " in column " + std::to_string(c + 1));
    }
    // A row with a column more or less than the first would shift or misread values.
    std::size_t count = needed;
    while (tokens.next(token)) ++count;
    if (count != width)
      src.fail_at_line(lines.line(),
                       "XYZ: " + std::to_string(count) + " columns where the first line has " + std::to_string(width));
    raw.positions.emplace_back(v[0], v[1], v[2]);
    if (has_normals) raw.normals.emplace_back(float(v[3]), float(v[4]), float(v[5]));
    if (has_colors) raw.colors.push_back({to_channel(v[6]), to_channel(v[7]), to_channel(v[8])});
  }
  return raw;
}

}  // namespace pcsketch::io::detail
