#pragma once
// Streaming readers: a format hands its points over in chunks, in file order, without building a RawCloud; the
// consumer (src/io/stream_read.cpp) keeps what it needs. Memory then grows with what is kept, not with the file.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "raw_cloud.h"

namespace pcsketch::io::detail {

class PointSink;

/// What the header says, before any point is handed over, and how to walk the points.
struct StreamHeader {
  std::uint64_t count = 0;  ///< points the file holds (checked against the file size)
  bool has_normals = false;
  bool has_colors = false;
  std::string format;
  std::vector<std::string> other_attributes;
  /// Hands every point to `sink` in file order, `chunk_points` at a time (stream_ply, stream_las).
  /// A text format's may keep what its first pass learnt (the layout) for the next.
  std::function<void(const Source& source, std::size_t chunk_points, PointSink& sink)> stream;
  /// Formats with fixed-size records (LAS): the chunks carry positions and classes only; after thinning, this reads
  /// the colours (when `colors`) and the attributes of the kept points (ascending file indices) from their records.
  /// `colour_max`: the largest colour channel in the file (PointChunk::colour_max). nullptr: the chunks carry the
  /// colours and the format has no per-point attributes.
  void (*read_kept)(const Source& source, std::span<const std::uint64_t> kept, std::uint16_t colour_max, bool colors,
                    PointCloud& cloud) = nullptr;
  bool has_classes = false;  ///< the chunks carry a classification per point (--classes, --drop-classes)
  /// Text formats (XYZ): the count above is an estimate for the budget decision, and the layout is known only once
  /// every row was read. Called after the first pass with the points it saw: sets the exact count, has_normals,
  /// has_colors, has_intensity, other_attributes, columns and warnings. nullptr: the header is exact.
  std::function<void(StreamHeader& header, std::uint64_t points)> surveyed;
  bool has_intensity = false;  ///< the chunks carry an intensity per point (kept as the "intensity" attribute)
  std::string columns;         ///< text formats: ReadResult::columns
  Warnings warnings;           ///< what the reader assumed (a guessed layout), before the read's own warnings
  /// Text formats: the most points the file can hold (0: `count` is exact). The budget decision and the survey's
  /// sample stride take it, not the estimate, which may fall short.
  std::uint64_t max_count = 0;
  std::uint64_t most() const { return std::max(count, max_count); }
};

/// One chunk of consecutive points; `normals`, `colors` and `classes` are empty when the chunks carry none.
struct PointChunk {
  std::uint64_t first = 0;  ///< file index of positions[0]
  std::span<const Vec3d> positions;
  std::span<const Vec3f> normals;
  std::span<const Rgb8> colors;
  std::span<const std::uint8_t> classes;  ///< LAS: the classification of each point
  std::span<const float> intensity;       ///< XYZ: the intensity column
  std::uint16_t colour_max = 0;           ///< LAS: the largest colour channel of the chunk's records (16-bit or 8-bit?)
};

/// Receives the chunks in file order; throwing stops the stream.
class PointSink {
 public:
  virtual ~PointSink() = default;
  virtual void points(const PointChunk& chunk) = 0;
};

/// Releases the pages of `bytes` wholly inside [from, to) (a mapped file read front to back); returns the offset up
/// to which pages are released, the `from` of the next call.
std::size_t release_pages(std::string_view bytes, std::size_t from, std::size_t to);

/// How stream_chunks may call its `read`: in file order, or for any index from any thread (fixed-size binary
/// records), each chunk then decoded in parallel.
enum class Decode : std::uint8_t { file_order, any_order };

/// Points first .. first + n − 1 from `read(index, position, normal or nullptr, colour or nullptr)` into
/// positions[0, n) and, where given, normals and colours; in parallel with Decode::any_order.
template <class Read>
void decode_points(std::uint64_t first, std::size_t n, const Read& read, Vec3d* positions, Vec3f* normals, Rgb8* colors,
                   Decode decode) {
  const auto decode_range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      read(first + i, positions[i], normals ? &normals[i] : nullptr, colors ? &colors[i] : nullptr);
  };
  if (decode == Decode::any_order)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192),
                      [&](const tbb::blocked_range<std::size_t>& r) { decode_range(r.begin(), r.end()); });
  else
    decode_range(0, n);
}

/// The chunk loop of the readers whose chunks carry positions, normals and colours (PLY, PCD):
/// `read(index, position, normal or nullptr, colour or nullptr)` decodes the points, in file order unless `decode`
/// says any order; `end_byte(n)` is the offset where the first n points end, up to which pages are released after
/// each chunk.
template <class Read, class EndByte>
void stream_chunks(const Source& src, std::uint64_t count, std::size_t chunk_points, bool has_normals, bool has_colors,
                   PointSink& sink, Read&& read, EndByte&& end_byte, Decode decode = Decode::file_order) {
  chunk_points = std::max<std::size_t>(chunk_points, 1);
  // Two sets of buffers: a chunk is decoded while the sink takes the one before, one chunk at a time.
  struct Buffers {
    std::vector<Vec3d> positions;
    std::vector<Vec3f> normals;
    std::vector<Rgb8> colors;
  };
  std::array<Buffers, 2> buffers;
  for (Buffers& b : buffers) {
    b.positions.resize(chunk_points);
    b.normals.resize(has_normals ? chunk_points : 0);
    b.colors.resize(has_colors ? chunk_points : 0);
  }
  std::size_t released = 0;
  tbb::task_group sinking;
  try {
    for (std::uint64_t first = 0; first < count; first += chunk_points) {
      Buffers& b = buffers[first / chunk_points % 2];
      const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk_points, count - first));
      decode_points(first, n, read, b.positions.data(), has_normals ? b.normals.data() : nullptr,
                    has_colors ? b.colors.data() : nullptr, decode);
      if (src.mapped) released = release_pages(src.bytes, released, end_byte(first + n));
      sinking.wait();  // the chunk before is taken: its buffers are free for the next
      sinking.run([&sink, &b, first, n] {
        sink.points({.first = first,
                     .positions = std::span(b.positions).first(n),
                     .normals = std::span(b.normals).first(b.normals.empty() ? 0 : n),
                     .colors = std::span(b.colors).first(b.colors.empty() ? 0 : n)});
      });
    }
  } catch (...) {
    sinking.wait();  // the sink's own exception, from the chunk before, wins
    throw;
  }
  sinking.wait();
}

/// At most this many positions (every n-th point) are sampled for the robust box of the resolution rule.
inline constexpr std::uint64_t kSurveySample = 1u << 18;

/// Sides of the box from 0.5 % to 99.5 % of each coordinate of `sample` (far outliers do not widen it).
Vec3d robust_extent(std::vector<Vec3d> sample);

/// Why the resolution rule thinned a file of `count` points ("2097152 points budget for a 1024x1024 image, …").
std::string resolution_reason(const OutputResolution& resolution, std::uint64_t count);

/// Streaming readers (PLY, LAS, ascii and binary PCD and the XYZ family; binary_compressed PCD, OFF and OBJ are read
/// whole). The header of a file the reader can stream, or nullopt (another format or layout); throws the
/// reader's error for a malformed header or a count the file cannot hold. stream_ply() / stream_las() / stream_pcd()
/// then hand every point to `sink`, `chunk_points` at a time; when `source.mapped`, the pages already read are released
/// (madvise) so that the mapping does not stay resident. las_read_kept() is LAS's StreamHeader::read_kept.
std::optional<StreamHeader> ply_stream_header(const Source& source);
std::optional<std::uint64_t> ply_header_count(const Source& source);  ///< any PLY layout; nullopt: not PLY
void stream_ply(const Source& source, std::size_t chunk_points, PointSink& sink);
std::optional<StreamHeader> las_stream_header(const Source& source);
void stream_las(const Source& source, std::size_t chunk_points, PointSink& sink);
std::optional<StreamHeader> pcd_stream_header(const Source& source);
void stream_pcd(const Source& source, std::size_t chunk_points, PointSink& sink);
std::optional<std::uint64_t> pcd_header_count(const Source& source);  ///< any PCD layout; nullopt: not PCD
/// The XYZ family: the header of a file read as XYZ (by its extension, no other magic), its count estimated from the
/// file size (docs/io.md); StreamHeader::surveyed completes it after the first pass.
std::optional<StreamHeader> xyz_stream_header(const Source& source);
/// Whether the whole read would read `source` as the XYZ family (throws its error for an empty or unknown file).
bool reads_as_xyz(const Source& source);
/// The rows of an XYZ-family text from the lines holding 256 evenly spaced offsets, each counting 1/length rows
/// per byte (within a few percent of the data rows); nullopt for a text of one line.
std::optional<std::uint64_t> sampled_rows(const Source& source);
void las_read_kept(const Source& source, std::span<const std::uint64_t> kept, std::uint16_t colour_max, bool colors,
                   PointCloud& cloud);

/// The whole streamed read: nullopt when the file is not streamable or `options` ask for no thinning this file
/// needs (then the in-memory read runs, and normal clouds read exactly as before); else the thinned cloud.
/// `chunk_points`: points per chunk (tests pass tiny ones; the result does not depend on it).
std::optional<ReadResult> read_streamed(const Source& source, const ReadOptions& options, std::size_t chunk_points);

}  // namespace pcsketch::io::detail
