// Streamed read of the XYZ family: the rows handed over in chunks, two passes over the mapped text. A text file has
// no count and, without --columns or a header row, no layout until every row was seen: the header's count is an
// estimate for the budget decision, and the first pass gathers the statistics the layout guess needs
// (ColumnStats), so that the second pass reads the columns exactly as the whole read would.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "point_stream.h"
#include "xyz.h"

namespace pcsketch::io::detail {
namespace {

/// Data lines whose length the count estimate looks at, and lines sampled through the file by sampled_rows.
constexpr std::size_t kEstimateLines = 1024, kSampledLines = 256;

/// The rows of a file before they are read: an estimate (for progress) and a bound no file can pass.
struct RowCount {
  std::uint64_t estimate = 0;
  std::uint64_t most = 0;
};

// The estimate is the file size over the shortest of the first data lines (with its line end); later lines may be
// shorter, so it can fall short. The bound: every row has the columns of the first (XyzRows checks it), and a column
// takes at least a byte and a separator or line end. A file of fewer lines is counted. Never allocates: the count
// that sizes anything is the one the first pass counted.
RowCount estimate_rows(const Source& src) {
  LineReader lines(skip_bom(src.bytes), 1, src.path);
  std::string_view line, token;
  std::size_t before = lines.consumed(src.bytes), shortest = std::numeric_limits<std::size_t>::max(), columns = 3;
  std::uint64_t rows = 0;
  try {
    while (rows < kEstimateLines) {
      if (!lines.next(line)) return {rows, rows};
      const std::size_t bytes = lines.consumed(src.bytes) - before;
      before += bytes;
      if (is_comment_or_blank(line)) continue;
      shortest = std::min(shortest, bytes);
      if (++rows < 2) continue;  // the first may be a header row or a PTS count line
      std::size_t n = 0;
      for (Tokens tokens(line, true); tokens.next(token);) ++n;
      columns = std::max<std::size_t>(3, n);
    }
  } catch (const Error&) {
    return {rows, rows};  // an overlong line: the first pass reports it, after any error on an earlier line
  }
  return {src.bytes.size() / shortest, (src.bytes.size() + 1) / (2 * columns)};
}

// What the first pass learns for the second.
struct XyzState {
  std::optional<ColumnStats> stats;  ///< of every row; empty before the first pass or for a file without rows
  XyzLayout layout;
  std::vector<std::string> unread;
  bool surveyed = false;
};

// The chunks' buffers; the second pass fills normals, colours and intensity when the layout has them.
struct XyzChunk {
  XyzChunk(std::size_t n, const XyzFields* f)
      : positions(n),
        normals(f && f->has_normals ? n : 0),
        colors(f && f->has_colors ? n : 0),
        intensity(f && f->intensity < f->width ? n : 0) {}
  std::vector<Vec3d> positions;
  std::vector<Vec3f> normals;
  std::vector<Rgb8> colors;
  std::vector<float> intensity;
};

void stream_xyz(XyzState& state, const Source& src, std::size_t chunk_points, PointSink& sink) {
  chunk_points = std::max<std::size_t>(chunk_points, 1);
  const bool survey = !state.surveyed;
  std::optional<XyzFields> f;
  if (!survey && state.stats) f.emplace(state.layout, state.stats->width);
  const double scale = f ? colour_scale(*state.stats, *f) : 1.0;
  XyzChunk chunk(chunk_points, f ? &*f : nullptr);
  XyzRows rows(src);
  std::uint64_t first = 0;
  std::size_t n = 0, released = 0;
  const auto flush = [&] {
    sink.points({.first = first,
                 .positions = std::span(chunk.positions).first(n),
                 .normals = std::span(chunk.normals).first(chunk.normals.empty() ? 0 : n),
                 .colors = std::span(chunk.colors).first(chunk.colors.empty() ? 0 : n),
                 .intensity = std::span(chunk.intensity).first(chunk.intensity.empty() ? 0 : n)});
    first += n;
    n = 0;
    if (src.mapped) released = release_pages(src.bytes, released, rows.consumed());
  };
  while (rows.next(chunk.positions[n])) {
    const float* row = rows.row();
    if (survey) {
      if (!state.stats) state.stats.emplace(rows.width());
      state.stats->add(row);
    }
    if (!chunk.normals.empty()) chunk.normals[n] = Vec3f(row[f->normal[0]], row[f->normal[1]], row[f->normal[2]]);
    if (!chunk.colors.empty())
      chunk.colors[n] = {to_channel(scale * row[f->rgb[0]]), to_channel(scale * row[f->rgb[1]]),
                         to_channel(scale * row[f->rgb[2]])};
    if (!chunk.intensity.empty()) chunk.intensity[n] = row[f->intensity];
    if (++n == chunk_points) flush();
  }
  if (n > 0) flush();
  if (!survey) return;
  state.layout = rows.layout();
  state.unread = rows.unread();
  state.surveyed = true;
}

// StreamHeader::surveyed: the exact count, and the layout as the whole read decides it.
void complete(XyzState& state, const std::string& path, StreamHeader& header, std::uint64_t rows) {
  header.count = rows;
  if (!state.stats) return;  // no rows: the read fails as the whole read does
  XyzLayout& layout = state.layout;
  if (layout.columns.empty()) guess_layout(layout, *state.stats, header.format, path, header.warnings);
  const XyzFields f(layout, state.stats->width);
  header.has_normals = f.has_normals;
  header.has_colors = f.has_colors;
  header.has_intensity = f.intensity < f.width;
  header.other_attributes = f.not_kept(layout, state.unread);
  header.columns = describe(layout);
}

}  // namespace

std::optional<std::uint64_t> sampled_rows(const Source& source) {
  const std::string_view text = skip_bom(source.bytes);
  if (text.find('\n') == std::string_view::npos) return std::nullopt;  // one line: the read counts it
  // The line holding each of evenly spaced offsets: a line is hit as often as it is long, so each counts 1/length
  // rows (a file of long lines first and short ones after is not taken for one of long lines). Comments count none.
  double rows = 0;
  for (std::size_t s = 0; s < kSampledLines; ++s) {
    const std::size_t at = text.size() * (2 * s + 1) / (2 * kSampledLines);
    const std::size_t start = at == 0 ? 0 : text.rfind('\n', at - 1) + 1;  // npos + 1 = 0: the first line
    const std::size_t end = std::min(text.find('\n', at), text.size());
    if (!is_comment_or_blank(text.substr(start, end - start))) rows += 1.0 / static_cast<double>(end - start + 1);
  }
  return static_cast<std::uint64_t>(std::llround(rows * static_cast<double>(text.size()) / kSampledLines));
}

std::optional<StreamHeader> xyz_stream_header(const Source& source) {
  if (!reads_as_xyz(source)) return std::nullopt;
  const auto state = std::make_shared<XyzState>();
  StreamHeader header;
  const RowCount estimated = estimate_rows(source);
  header.count = estimated.estimate;
  header.max_count = estimated.most;
  header.format = xyz_format(source.path);
  header.stream = [state](const Source& src, std::size_t chunk_points, PointSink& sink) {
    stream_xyz(*state, src, chunk_points, sink);
  };
  header.surveyed = [state, path = source.path](StreamHeader& h, std::uint64_t rows) {
    complete(*state, path, h, rows);
  };
  return header;
}

}  // namespace pcsketch::io::detail
