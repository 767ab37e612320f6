// LAS 1.0-1.4 reader (ASPRS LAS specification 1.4 R15): the public header, VLRs skipped by their declared lengths,
// point data record formats 0-10. Compressed LAS (LAZ) is recognised and refused.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "point_stream.h"
#include "raw_cloud.h"

namespace pcsketch::io::detail {
namespace {

// Little-endian unsigned integer of `n` bytes at `offset`; the caller has checked that they lie in `bytes`.
std::uint64_t le(std::string_view bytes, std::size_t offset, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t(static_cast<unsigned char>(bytes[offset + i])) << (8 * i);
  return v;
}
double le_double(std::string_view bytes, std::size_t offset) { return std::bit_cast<double>(le(bytes, offset, 8)); }

// Public header fields (spec table 3/4), as byte offsets.
constexpr std::size_t kVersionMajor = 24, kVersionMinor = 25, kHeaderSize = 94, kOffsetToPoints = 96, kVlrCount = 100,
                      kPointFormat = 104, kRecordLength = 105, kLegacyCount = 107, kScale = 131, kOffset = 155,
                      kCount64 = 247;
constexpr std::size_t kHeader10 = 227;  ///< size of a 1.0-1.2 header
constexpr std::size_t kHeader14 = 375;  ///< size of a 1.4 header
constexpr std::size_t kVlrHeader = 54;  ///< reserved, user id, record id, length after header, description

/// Smallest record of each point data format 0-10 (spec tables 7-17).
constexpr std::array<std::size_t, 11> kRecordSize{20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};

/// Where a point format keeps its fields: formats 0-5 share one layout, 6-10 another.
struct PointLayout {
  bool extended;      ///< formats 6-10: 4-bit return numbers, a full classification byte
  int rgb;            ///< byte offset of red green blue (uint16 each), -1: none
  bool gps_time;      ///< a GPS time field (not kept)
  bool nir;           ///< a near-infrared channel (not kept)
  bool wave_packets;  ///< waveform packet fields (not kept)
};

PointLayout layout_of(unsigned format) {
  const bool gps = format != 0 && format != 2;
  const bool wave = format == 4 || format == 5 || format == 9 || format == 10;
  if (format < 6) return {false, format == 2 ? 20 : (format == 3 || format == 5) ? 28 : -1, gps, false, wave};
  return {true, (format == 7 || format == 8 || format == 10) ? 30 : -1, true, format == 8 || format == 10, wave};
}

struct Header {
  unsigned minor = 0;
  std::size_t header_size = 0, offset_to_points = 0, record_length = 0;
  unsigned format = 0;
  std::uint64_t count = 0;
  std::size_t count_field = 0;  ///< byte offset of the count used (for messages)
  Vec3d scale, offset;
};

void refuse_laz(const Source& src, std::size_t at, unsigned format) {
  src.fail_at_byte(at, "LAS: the file is LAZ, compressed LAS (point format " + std::to_string(format) +
                           "), which is not supported; decompress it to .las first");
}

// VLRs lie between the header and the points; each must end before the points start.
void check_vlrs(const Source& src, const Header& h) {
  const std::uint64_t declared = le(src.bytes, kVlrCount, 4);
  std::size_t at = h.header_size;
  for (std::uint64_t v = 0; v < declared; ++v) {
    const bool header_fits = at + kVlrHeader <= h.offset_to_points;
    const std::size_t end = header_fits ? at + kVlrHeader + le(src.bytes, at + 20, 2) : h.offset_to_points + 1;
    if (end > h.offset_to_points)
      src.fail_at_byte(at, "LAS: variable length record " + std::to_string(v + 1) + " of " + std::to_string(declared) +
                               " runs past the start of the point data (byte " + std::to_string(h.offset_to_points) +
                               ")");
    if (src.bytes.substr(at + 2, 16).starts_with("laszip encoded")) refuse_laz(src, at, h.format);
    at = end;
  }
}

std::uint64_t point_count(const Source& src, Header& h) {
  const std::uint64_t legacy = le(src.bytes, kLegacyCount, 4);
  h.count_field = kLegacyCount;
  if (h.minor < 4) return legacy;
  const std::uint64_t count = le(src.bytes, kCount64, 8);
  if (legacy != 0 && legacy != count)
    src.fail_at_byte(kLegacyCount, "LAS: the legacy point count " + std::to_string(legacy) +
                                       " disagrees with the 64-bit count " + std::to_string(count) + " (byte 247)");
  h.count_field = kCount64;
  return count;
}

Header read_header(const Source& src) {
  const std::string_view b = src.bytes;
  if (b.size() < kHeader10)
    src.fail_at_byte(b.size(), "LAS: file ends inside the header (" + std::to_string(b.size()) + " bytes; at least " +
                                   std::to_string(kHeader10) + " needed)");
  Header h;
  const auto major = static_cast<unsigned>(le(b, kVersionMajor, 1));
  h.minor = static_cast<unsigned>(le(b, kVersionMinor, 1));
  if (major != 1 || h.minor > 4)
    src.fail_at_byte(kVersionMajor, "LAS: version " + std::to_string(major) + "." + std::to_string(h.minor) +
                                        " is not supported (1.0 to 1.4)");
  const std::size_t needed = h.minor >= 4 ? kHeader14 : kHeader10;
  h.header_size = le(b, kHeaderSize, 2);
  if (h.header_size < needed || h.header_size > b.size())
    src.fail_at_byte(kHeaderSize, "LAS: header size " + std::to_string(h.header_size) + " is not between " +
                                      std::to_string(needed) + " and the file size " + std::to_string(b.size()));
  h.offset_to_points = le(b, kOffsetToPoints, 4);
  if (h.offset_to_points < h.header_size || h.offset_to_points > b.size())
    src.fail_at_byte(kOffsetToPoints, "LAS: offset to point data " + std::to_string(h.offset_to_points) +
                                          " is not between the header size " + std::to_string(h.header_size) +
                                          " and the file size " + std::to_string(b.size()));
  const auto format_byte = static_cast<unsigned>(le(b, kPointFormat, 1));
  // LAZ marks its point format with bit 7 (bit 6 in old LASzip versions).
  if (format_byte & 0xC0u) refuse_laz(src, kPointFormat, format_byte & 0x3Fu);
  h.format = format_byte;
  if (h.format >= kRecordSize.size())
    src.fail_at_byte(kPointFormat, "LAS: point data format " + std::to_string(h.format) + " is not one of 0-10");
  h.record_length = le(b, kRecordLength, 2);
  if (h.record_length < kRecordSize[h.format])
    src.fail_at_byte(kRecordLength, "LAS: point record length " + std::to_string(h.record_length) +
                                        " is smaller than the " + std::to_string(kRecordSize[h.format]) +
                                        " bytes of point format " + std::to_string(h.format));
  for (int a = 0; a < 3; ++a) {
    h.scale[a] = le_double(b, kScale + 8 * static_cast<std::size_t>(a));
    h.offset[a] = le_double(b, kOffset + 8 * static_cast<std::size_t>(a));
  }
  if (!h.scale.allFinite() || (h.scale.array() == 0.0).any())
    src.fail_at_byte(kScale, "LAS: a scale factor is zero or not finite");
  if (!h.offset.allFinite()) src.fail_at_byte(kOffset, "LAS: an offset is not finite");
  check_vlrs(src, h);
  // The count is checked against the bytes after the offset before anything is allocated.
  h.count = point_count(src, h);
  const std::uint64_t available = b.size() - h.offset_to_points;
  if (h.count > available / h.record_length)
    src.fail_at_byte(h.count_field, "LAS: header claims " + std::to_string(h.count) + " points of " +
                                        std::to_string(h.record_length) + " bytes from byte " +
                                        std::to_string(h.offset_to_points) + ", but only " + std::to_string(available) +
                                        " bytes follow (truncated file?)");
  return h;
}

std::vector<std::string> unkept(const PointLayout& layout, std::size_t extra_bytes) {
  std::vector<std::string> names{"number_of_returns", "scan_angle", "user_data", "point_source_id"};
  if (layout.gps_time) names.push_back("gps_time");
  if (layout.nir) names.push_back("nir");
  if (layout.wave_packets) names.push_back("wave_packets");
  if (extra_bytes > 0) names.push_back("extra bytes (" + std::to_string(extra_bytes) + " per point)");
  return names;
}

std::string format_name(const Header& h) {
  return "las 1." + std::to_string(h.minor) + " point format " + std::to_string(h.format);
}

/// The record of point `i` (the header's count was checked against the file size).
std::string_view record(const Source& src, const Header& h, std::uint64_t i) {
  return src.bytes.substr(h.offset_to_points + static_cast<std::size_t>(i) * h.record_length, h.record_length);
}

Vec3d position(const Header& h, std::string_view r) {
  Vec3d p;
  for (int a = 0; a < 3; ++a) {
    const auto q = static_cast<std::int32_t>(static_cast<std::uint32_t>(le(r, 4 * static_cast<std::size_t>(a), 4)));
    p[a] = h.offset[a] + h.scale[a] * q;
  }
  return p;
}

// Formats 0-5 keep flags in the top 3 bits of the classification byte.
std::uint8_t class_of(const PointLayout& layout, std::string_view r) {
  return static_cast<std::uint8_t>(layout.extended ? le(r, 16, 1) : le(r, 15, 1) & 0x1Fu);
}

std::array<std::uint16_t, 3> rgb16(const PointLayout& layout, std::string_view r) {
  std::array<std::uint16_t, 3> c{};
  for (std::size_t k = 0; k < 3; ++k)
    c[k] = static_cast<std::uint16_t>(le(r, static_cast<std::size_t>(layout.rgb) + 2 * k, 2));
  return c;
}

// The spec's colours are 16-bit; many writers store 8-bit values unscaled, which a maximum of 255 over the whole
// file betrays.
Rgb8 to_rgb8(const std::array<std::uint16_t, 3>& c, std::uint16_t colour_max) {
  const double to_8bit = colour_max <= 255 ? 1.0 : 255.0 / 65535.0;
  return {to_channel(c[0] * to_8bit), to_channel(c[1] * to_8bit), to_channel(c[2] * to_8bit)};
}

/// The attributes parse_las keeps, filled record by record.
struct Attributes {
  std::vector<float> classification, intensity, return_number;

  void add(const PointLayout& layout, std::string_view r) {
    classification.push_back(static_cast<float>(class_of(layout, r)));
    intensity.push_back(static_cast<float>(le(r, 12, 2)));
    const auto returns = static_cast<unsigned>(le(r, 14, 1));
    return_number.push_back(static_cast<float>(layout.extended ? returns & 0x0Fu : returns & 0x07u));
  }
  std::vector<PointAttribute> take() {
    return {{"classification", std::move(classification)},
            {"intensity", std::move(intensity)},
            {"return_number", std::move(return_number)}};
  }
};

}  // namespace

RawCloud parse_las(const Source& src, Want) {
  const Header h = read_header(src);
  const PointLayout layout = layout_of(h.format);
  RawCloud raw;
  raw.format = format_name(h);
  const auto n = static_cast<std::size_t>(h.count);
  raw.positions.resize(n);
  Attributes attributes;
  std::vector<std::array<std::uint16_t, 3>> rgb(layout.rgb >= 0 ? n : 0);
  std::uint16_t colour_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string_view r = record(src, h, i);
    raw.positions[i] = position(h, r);
    attributes.add(layout, r);
    if (layout.rgb < 0) continue;
    rgb[i] = rgb16(layout, r);
    colour_max = std::max({colour_max, rgb[i][0], rgb[i][1], rgb[i][2]});
  }
  for (const auto& c : rgb) raw.colors.push_back(to_rgb8(c, colour_max));
  raw.attributes = attributes.take();
  raw.other_attributes = unkept(layout, h.record_length - kRecordSize[h.format]);
  return raw;
}

std::optional<StreamHeader> las_stream_header(const Source& src) {
  if (!src.bytes.starts_with("LASF")) return std::nullopt;
  const Header h = read_header(src);
  const PointLayout layout = layout_of(h.format);
  return StreamHeader{.count = h.count,
                      .has_colors = layout.rgb >= 0,
                      .format = format_name(h),
                      .other_attributes = unkept(layout, h.record_length - kRecordSize[h.format]),
                      .stream = stream_las,
                      .read_kept = las_read_kept,
                      .has_classes = true};
}

void stream_las(const Source& src, std::size_t chunk_points, PointSink& sink) {
  const Header h = read_header(src);
  const PointLayout layout = layout_of(h.format);
  chunk_points = std::max<std::size_t>(chunk_points, 1);
  std::vector<Vec3d> positions(chunk_points);
  std::vector<std::uint8_t> classes(chunk_points);
  std::size_t released = 0;
  for (std::uint64_t first = 0; first < h.count; first += chunk_points) {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk_points, h.count - first));
    std::uint16_t colour_max = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::string_view r = record(src, h, first + i);
      positions[i] = position(h, r);
      classes[i] = class_of(layout, r);
      if (layout.rgb < 0) continue;
      const std::array<std::uint16_t, 3> c = rgb16(layout, r);
      colour_max = std::max({colour_max, c[0], c[1], c[2]});
    }
    sink.points({.first = first,
                 .positions = std::span(positions).first(n),
                 .classes = std::span(classes).first(n),
                 .colour_max = colour_max});
    if (src.mapped)
      released = release_pages(src.bytes, released,
                               h.offset_to_points + static_cast<std::size_t>(first + n) * h.record_length);
  }
}

void las_read_kept(const Source& src, std::span<const std::uint64_t> kept, std::uint16_t colour_max, bool colors,
                   PointCloud& cloud) {
  const Header h = read_header(src);
  const PointLayout layout = layout_of(h.format);
  Attributes attributes;
  std::size_t released = 0;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const std::string_view r = record(src, h, kept[k]);
    attributes.add(layout, r);
    if (colors && layout.rgb >= 0) cloud.colors.push_back(to_rgb8(rgb16(layout, r), colour_max));
    // The kept records are visited in file order: their pages are released behind the reading as in the passes.
    if (src.mapped && k % 4096 == 4095)
      released = release_pages(src.bytes, released, static_cast<std::size_t>(r.data() - src.bytes.data()));
  }
  cloud.attributes = attributes.take();
}

}  // namespace pcsketch::io::detail
