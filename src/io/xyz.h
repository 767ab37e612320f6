#pragma once
// The XYZ family (XYZ / PTS / TXT / CSV / ASC), shared by the whole read (xyz.cpp) and the streamed one
// (xyz_stream.cpp): the rows of a file, checked and parsed alike by both, and what the layout makes of them.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "columns.h"
#include "raw_cloud.h"
#include "text_scan.h"

namespace pcsketch::io::detail {

/// A line without data: blank, separators only, or a '#' or "//" comment.
bool is_comment_or_blank(std::string_view line);

/// The format name of a text file: its extension without the dot ("xyz", "pts", "csv"…).
std::string xyz_format(const std::string& path);

/// The layout as read: what each column holds, and the names of a header row (for the columns not kept).
struct XyzLayout {
  std::vector<Column> columns;  ///< empty until known
  std::vector<std::string> names;
  std::string how;  ///< "--columns", "header", "the PTS convention" or "guessed from the values"
};

/// The data rows of a text file, in order: comments, blank lines, a header row and a PTS count line skipped, every
/// row checked (the same errors, naming the same line, in the whole and the streamed read).
class XyzRows {
 public:
  explicit XyzRows(const Source& source);

  /// The next data row: x y z into `p`, its first width() columns as float into row() (Skip columns 0); false at
  /// the end of the file.
  bool next(Vec3d& p);
  const float* row() const { return row_.data(); }
  /// Columns read from each row, fixed by the first data row (0 before it): the layout's, or up to 9 to guess from.
  std::size_t width() const { return row_.size(); }
  XyzLayout& layout() { return layout_; }
  /// "column 10"…: the columns past those read when guessing, not kept.
  const std::vector<std::string>& unread() const { return unread_; }
  /// Bytes of the source read so far.
  std::size_t consumed() const { return lines_.consumed(src_.bytes); }

 private:
  bool data_line(std::string_view line);
  void first_row(std::string_view line);

  const Source& src_;
  XyzLayout layout_;
  LineReader lines_;
  bool first_data_line_ = true;
  std::size_t line_columns_ = 0;  ///< columns every line has: those of the first data line
  std::array<std::size_t, 3> xyz_{0, 1, 2};
  std::vector<float> row_;
  std::vector<std::string> unread_;
};

/// Where the layout puts normals, colours and intensity (a column index, or the width when absent).
struct XyzFields {
  XyzFields(const XyzLayout& layout, std::size_t columns);
  /// RawCloud::other_attributes: `unread` (XyzRows::unread()), then the columns read but not kept.
  std::vector<std::string> not_kept(const XyzLayout& layout, std::vector<std::string> unread) const;

  std::size_t width;
  std::array<std::size_t, 3> normal, rgb;
  std::size_t intensity;
  bool has_normals, has_colors;
};

/// Colours in [0, 1] with a fraction somewhere are scaled to 0-255; whole numbers are taken as 0-255.
double colour_scale(const ColumnStats& stats, const XyzFields& fields);

/// RawCloud::columns: "x,y,z,r,g,b (header)".
std::string describe(const XyzLayout& layout);

/// The layout when neither --columns nor a header gave it: guessed from the values (ColumnStats of every row).
void guess_layout(XyzLayout& layout, const ColumnStats& stats, const std::string& format, const std::string& path,
                  Warnings& warnings);

}  // namespace pcsketch::io::detail
