// LAS 1.0-1.4 reader (ASPRS LAS specification 1.4 R15): the public header, VLRs skipped by their declared lengths,
// point data record formats 0-10. Compressed LAS (LAZ) is recognised and refused.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

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

void list_unkept(RawCloud& raw, const PointLayout& layout, std::size_t extra_bytes) {
  for (const char* name : {"number_of_returns", "scan_angle", "user_data", "point_source_id"})
    raw.other_attributes.push_back(name);
  if (layout.gps_time) raw.other_attributes.push_back("gps_time");
  if (layout.nir) raw.other_attributes.push_back("nir");
  if (layout.wave_packets) raw.other_attributes.push_back("wave_packets");
  if (extra_bytes > 0) raw.other_attributes.push_back("extra bytes (" + std::to_string(extra_bytes) + " per point)");
}

}  // namespace

RawCloud parse_las(const Source& src, Want) {
  const Header h = read_header(src);
  const PointLayout layout = layout_of(h.format);
  RawCloud raw;
  raw.format = "las 1." + std::to_string(h.minor) + " point format " + std::to_string(h.format);
  const auto n = static_cast<std::size_t>(h.count);
  raw.positions.resize(n);
  std::vector<float> classification(n), intensity(n), return_number(n);
  std::vector<std::array<std::uint16_t, 3>> rgb(layout.rgb >= 0 ? n : 0);
  std::uint16_t rgb_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string_view r = src.bytes.substr(h.offset_to_points + i * h.record_length, h.record_length);
    for (int a = 0; a < 3; ++a) {
      const auto q = static_cast<std::int32_t>(static_cast<std::uint32_t>(le(r, 4 * static_cast<std::size_t>(a), 4)));
      raw.positions[i][a] = h.offset[a] + h.scale[a] * q;
    }
    intensity[i] = static_cast<float>(le(r, 12, 2));
    const auto returns = static_cast<unsigned>(le(r, 14, 1));
    return_number[i] = static_cast<float>(layout.extended ? returns & 0x0Fu : returns & 0x07u);
    // Formats 0-5 keep flags in the top 3 bits of the classification byte.
    classification[i] = static_cast<float>(layout.extended ? le(r, 16, 1) : le(r, 15, 1) & 0x1Fu);
    if (layout.rgb < 0) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      rgb[i][c] = static_cast<std::uint16_t>(le(r, static_cast<std::size_t>(layout.rgb) + 2 * c, 2));
      rgb_max = std::max(rgb_max, rgb[i][c]);
    }
  }
  // The spec's colours are 16-bit; many writers store 8-bit values unscaled, which a maximum of 255 betrays.
  const double to_8bit = rgb_max <= 255 ? 1.0 : 255.0 / 65535.0;
  for (const auto& c : rgb)
    raw.colors.push_back({to_channel(c[0] * to_8bit), to_channel(c[1] * to_8bit), to_channel(c[2] * to_8bit)});
  raw.attributes.push_back({"classification", std::move(classification)});
  raw.attributes.push_back({"intensity", std::move(intensity)});
  raw.attributes.push_back({"return_number", std::move(return_number)});
  list_unkept(raw, layout, h.record_length - kRecordSize[h.format]);
  return raw;
}

}  // namespace pcsketch::io::detail
