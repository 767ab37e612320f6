// PCD reader (Point Cloud Library): DATA ascii, binary and binary_compressed (LZF), fields x y z, normal_x/y/z and
// the packed rgb/rgba colour.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "ply_types.h"
#include "point_stream.h"
#include "raw_cloud.h"
#include "text_scan.h"

namespace pcsketch::io::detail {
namespace {

struct Field {
  std::string name;
  std::size_t size = 4;
  char type = 'F';
  std::size_t count = 1;
  std::size_t offset = 0;  ///< in a binary record (point-major layout)
  PlyScalar scalar = PlyScalar::F32;
};

/// LZF decompression (liblzf's format, as PCL writes it) into exactly `out.size()` bytes; false on corrupt input.
bool lzf_decompress(std::string_view in, std::vector<char>& out) {
  std::size_t ip = 0, op = 0;
  while (ip < in.size()) {
    const unsigned ctrl = static_cast<unsigned char>(in[ip++]);
    if (ctrl < 32) {  // a run of ctrl + 1 literal bytes
      const std::size_t len = ctrl + 1;
      if (len > in.size() - ip || len > out.size() - op) return false;
      std::memcpy(out.data() + op, in.data() + ip, len);
      ip += len;
      op += len;
      continue;
    }
    std::size_t len = ctrl >> 5;  // a back reference
    if (len == 7) {
      if (ip >= in.size()) return false;
      len += static_cast<unsigned char>(in[ip++]);
    }
    if (ip >= in.size()) return false;
    const std::size_t back = ((ctrl & 0x1fu) << 8) + static_cast<unsigned char>(in[ip++]) + 1;
    len += 2;
    if (back > op || len > out.size() - op) return false;
    for (std::size_t k = 0; k < len; ++k, ++op) out[op] = out[op - back];  // may overlap: byte by byte
  }
  return op == out.size();
}

std::optional<PlyScalar> scalar_of(char type, std::size_t size) {
  if (type == 'F')
    return size == 4 ? std::optional(PlyScalar::F32) : size == 8 ? std::optional(PlyScalar::F64) : std::nullopt;
  const bool u = type == 'U';
  if (type != 'U' && type != 'I') return std::nullopt;
  switch (size) {
    case 1:
      return u ? PlyScalar::U8 : PlyScalar::I8;
    case 2:
      return u ? PlyScalar::U16 : PlyScalar::I16;
    case 4:
      return u ? PlyScalar::U32 : PlyScalar::I32;
    default:
      return std::nullopt;
  }
}

// rgb/rgba hold 0x00RRGGBB in the bits of a float (or a uint32).
Rgb8 unpack_rgb(double value, PlyScalar type) {
  std::uint32_t bits = 0;
  if (type == PlyScalar::F32) {
    bits = std::bit_cast<std::uint32_t>(static_cast<float>(value));
  } else if (value >= 0 && value <= 4294967295.0) {
    bits = static_cast<std::uint32_t>(value);
  }
  return {static_cast<std::uint8_t>(bits >> 16), static_cast<std::uint8_t>(bits >> 8), static_cast<std::uint8_t>(bits)};
}

/// The LZF body of a binary_compressed PCD starting at `body`, which must unpack to `size_expected` bytes.
std::vector<char> unpack(const Source& src, std::size_t body, std::uint64_t size_expected) {
  const std::string_view bytes = src.bytes.substr(body);
  if (bytes.size() < 8) src.fail_at_byte(body, "PCD: compressed body lacks its 8-byte size header");
  const auto compressed = load_swapped<std::uint32_t>(bytes.data(), false);
  const auto size = load_swapped<std::uint32_t>(bytes.data() + 4, false);
  if (compressed > bytes.size() - 8)
    src.fail_at_byte(body, "PCD: compressed size " + std::to_string(compressed) + " exceeds the file (truncated?)");
  if (size != size_expected)
    src.fail_at_byte(body + 4, "PCD: uncompressed size " + std::to_string(size) + " is not POINTS x record size " +
                                   std::to_string(size_expected));
  // LZF expands at most 88 times (264 bytes from a 3-byte back reference): bounds the allocation.
  if (size > 88ull * compressed + 32) src.fail_at_byte(body + 4, "PCD: uncompressed size impossible for LZF");
  std::vector<char> unpacked(size);
  if (!lzf_decompress(bytes.substr(8, compressed), unpacked))
    src.fail_at_byte(body + 8, "PCD: corrupt LZF-compressed body");
  return unpacked;
}

/// The header: fields and their offsets in a record, the count (checked against the bytes after the header), where
/// the body starts.
struct PcdHeader {
  std::vector<Field> fields;
  std::uint64_t points = 0;
  std::string data;               ///< ascii, binary or binary_compressed
  std::size_t record = 0;         ///< bytes of a binary record
  std::size_t body = 0;           ///< byte offset of the points
  std::uint64_t header_line = 0;  ///< the DATA line
  std::array<const Field*, 3> xyz{}, nrm{};
  const Field* rgb = nullptr;
  bool has_normals = false;
  std::vector<std::string> other_attributes;

  PcdHeader() = default;
  PcdHeader(const PcdHeader&) = delete;  // the Field pointers point into `fields`
};

// The header's keyword lines, up to and including DATA, into `h`; returns the reader after it.
void read_keywords(const Source& src, LineReader& lines, PcdHeader& h) {
  std::string_view line, keyword, token;
  std::uint64_t width = 0, height = 1;
  bool have_points = false;
  std::vector<Field>& fields = h.fields;
  while (h.data.empty()) {
    if (!lines.next(line)) src.fail_at_line(lines.line() + 1, "PCD: header has no DATA line");
    if (line.starts_with("#")) continue;
    Tokens tokens(line, false);
    if (!tokens.next(keyword)) continue;
    const auto fail = [&](const std::string& m) { src.fail_at_line(lines.line(), "PCD: " + m); };
    std::vector<std::string_view> values;
    while (tokens.next(token)) values.push_back(token);
    const auto per_field = [&](auto&& set) {
      if (values.size() != fields.size()) fail(std::string(keyword) + " needs one value per field");
      for (std::size_t i = 0; i < values.size(); ++i) set(fields[i], values[i]);
    };
    const auto one_uint = [&](std::uint64_t& out) {
      if (values.size() != 1 || !parse_uint(values[0], out)) fail(std::string(keyword) + " needs one integer");
    };
    if (keyword == "VERSION" || keyword == "VIEWPOINT") {
      continue;
    } else if (keyword == "FIELDS") {
      if (values.empty()) fail("FIELDS is empty");
      for (const std::string_view v : values) fields.push_back(Field{std::string(v)});
    } else if (keyword == "SIZE" || keyword == "COUNT") {
      per_field([&](Field& f, std::string_view v) {
        std::uint64_t x = 0;
        if (!parse_uint(v, x) || x == 0 || x > 1024) fail("invalid " + std::string(keyword) + " " + quote(v));
        (keyword == "SIZE" ? f.size : f.count) = x;
      });
    } else if (keyword == "TYPE") {
      per_field([&](Field& f, std::string_view v) {
        if (v.size() != 1) fail("invalid TYPE " + quote(v));
        f.type = v[0];
      });
    } else if (keyword == "WIDTH") {
      one_uint(width);
    } else if (keyword == "HEIGHT") {
      one_uint(height);
    } else if (keyword == "POINTS") {
      one_uint(h.points);
      have_points = true;
    } else if (keyword == "DATA") {
      if (values.size() != 1) fail("DATA needs ascii, binary or binary_compressed");
      h.data = values[0];
      if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed")
        fail("unknown DATA " + quote(h.data));
    } else {
      fail("unknown header keyword " + quote(keyword));
    }
  }
  h.header_line = lines.line();
  if (fields.empty()) src.fail_at_line(h.header_line, "PCD: header has no FIELDS line");
  if (!have_points) {
    if (height != 0 && width > 0xffffffffull / height)
      src.fail_at_line(h.header_line, "PCD: WIDTH x HEIGHT is too large");
    h.points = width * height;
  }
}

// Types, offsets and the fields kept; the count against the bytes after the header.
void read_header(const Source& src, PcdHeader& h) {
  LineReader lines(src.bytes, 1, src.path);
  read_keywords(src, lines, h);
  for (Field& f : h.fields) {
    const auto s = scalar_of(f.type, f.size);
    if (!s) src.fail_at_line(h.header_line, "PCD: field " + quote(f.name) + " has unsupported TYPE/SIZE");
    f.scalar = *s;
    f.offset = h.record;
    h.record += f.size * f.count;
  }
  if (h.record > (1u << 20)) src.fail_at_line(h.header_line, "PCD: a point record of more than 1 MiB");
  const auto find = [&](std::initializer_list<std::string_view> names) -> const Field* {
    for (const Field& f : h.fields)
      if (std::find(names.begin(), names.end(), f.name) != names.end()) return &f;
    return nullptr;
  };
  h.xyz = {find({"x"}), find({"y"}), find({"z"})};
  h.nrm = {find({"normal_x", "nx"}), find({"normal_y", "ny"}), find({"normal_z", "nz"})};
  h.rgb = find({"rgb", "rgba"});
  if (!h.xyz[0] || !h.xyz[1] || !h.xyz[2]) src.fail_at_line(h.header_line, "PCD: FIELDS lacks one of x, y, z");
  h.has_normals = h.nrm[0] && h.nrm[1] && h.nrm[2];
  for (const Field& f : h.fields)
    if (std::find(h.xyz.begin(), h.xyz.end(), &f) == h.xyz.end() &&
        (!h.has_normals || std::find(h.nrm.begin(), h.nrm.end(), &f) == h.nrm.end()) && &f != h.rgb)
      h.other_attributes.push_back(f.name);

  // Check the point count against the bytes left before allocating anything sized by it.
  h.body = lines.consumed(src.bytes);
  const std::uint64_t left = src.bytes.size() - h.body;
  const std::uint64_t min_bytes = h.data == "ascii" ? 2 * h.fields.size() : h.data == "binary" ? h.record : 1;
  const std::uint64_t budget = left + (h.data == "ascii" ? 1 : 0);  // the last ascii value may end the file
  if (h.points > 0xffffffffull || h.points > budget / min_bytes)
    src.fail_at_byte(h.body, "PCD: header claims " + std::to_string(h.points) + " points, but only " +
                                 std::to_string(left) + " bytes follow the header (truncated file?)");
}

/// One point's position, normal (when `n`) and colour (when `c`); `value_of(field)` reads a field's first value.
template <class ValueOf>
void decode(const PcdHeader& h, ValueOf&& value_of, Vec3d& p, Vec3f* n, Rgb8* c) {
  p = Vec3d(value_of(*h.xyz[0]), value_of(*h.xyz[1]), value_of(*h.xyz[2]));
  if (n != nullptr) *n = Vec3f(float(value_of(*h.nrm[0])), float(value_of(*h.nrm[1])), float(value_of(*h.nrm[2])));
  if (c != nullptr) *c = unpack_rgb(value_of(*h.rgb), h.rgb->scalar);
}

/// The points of an ascii body, one a line (blank lines skipped), read in order; shared by the whole and the
/// streamed read so that both fail alike.
class AsciiRows {
 public:
  AsciiRows(const Source& src, const PcdHeader& h)
      : src_(src), h_(h), lines_(src.bytes.substr(h.body), h.header_line + 1, src.path) {
    for (const Field& f : h.fields) {
      first_value_.push_back(values_.size());
      values_.resize(values_.size() + f.count);
    }
  }

  /// Point `i` (the i-th call): its position, normal (when `n`) and colour (when `c`).
  void read(std::uint64_t i, Vec3d& p, Vec3f* n, Rgb8* c) {
    std::string_view line, token;
    do {
      if (!lines_.next(line))
        src_.fail_at_line(lines_.line() + 1,
                          "PCD: file ends after " + std::to_string(i) + " of " + std::to_string(h_.points) + " points");
    } while (line.find_first_not_of(" \t\r") == std::string_view::npos);
    Tokens tokens(line, false);
    for (double& v : values_) {
      if (!tokens.next(token))
        src_.fail_at_line(lines_.line(), "PCD: too few values (need " + std::to_string(values_.size()) + ")");
      if (!parse_double(token, v)) src_.fail_at_line(lines_.line(), "PCD: " + bad_number(token));
    }
    // A row holds exactly the COUNTs' sum: a value more means the fields are not what the header says.
    if (!tokens.done()) {
      std::size_t count = values_.size();
      while (tokens.next(token)) ++count;
      src_.fail_at_line(lines_.line(), "PCD: too many values (" + std::to_string(count) + "; the fields need " +
                                           std::to_string(values_.size()) + ")");
    }
    const auto value_of = [&](const Field& f) {
      return values_[first_value_[static_cast<std::size_t>(&f - h_.fields.data())]];
    };
    decode(h_, value_of, p, n, c);
  }

  /// Offset of the first byte not read yet (past the last point's line).
  std::size_t end() const { return h_.body + lines_.offset(); }

 private:
  const Source& src_;
  const PcdHeader& h_;
  LineReader lines_;
  std::vector<std::size_t> first_value_;  ///< per field, the index of its first value on a line
  std::vector<double> values_;            ///< the values of the line last read
};

}  // namespace

bool sniff_pcd(std::string_view head) {
  while (head.starts_with("#")) {
    const std::size_t eol = head.find('\n');
    if (eol == std::string_view::npos) return false;
    head.remove_prefix(eol + 1);
  }
  return head.starts_with("VERSION") || head.starts_with("FIELDS");
}

RawCloud parse_pcd(const Source& src, Want) {
  PcdHeader h;
  read_header(src, h);
  const std::uint64_t points = h.points;
  RawCloud raw;
  raw.format = "pcd " + h.data;
  raw.other_attributes = h.other_attributes;
  // The compressed body's sizes are checked (and it is unpacked) before the point arrays are allocated.
  std::vector<char> unpacked;
  if (h.data == "binary_compressed") unpacked = unpack(src, h.body, points * h.record);
  raw.positions.resize(points);
  if (h.has_normals) raw.normals.resize(points);
  if (h.rgb) raw.colors.resize(points);

  const auto store = [&](std::size_t i, auto&& value_of) {
    decode(h, value_of, raw.positions[i], h.has_normals ? &raw.normals[i] : nullptr, h.rgb ? &raw.colors[i] : nullptr);
  };
  if (h.data == "ascii") {
    AsciiRows rows(src, h);
    for (std::size_t i = 0; i < points; ++i)
      rows.read(i, raw.positions[i], h.has_normals ? &raw.normals[i] : nullptr, h.rgb ? &raw.colors[i] : nullptr);
    return raw;
  }
  // Binary: point-major records. Compressed: field-major arrays (each field's values for every point in turn).
  std::string_view bytes = src.bytes.substr(h.body);
  if (h.data == "binary_compressed") {
    bytes = std::string_view(unpacked.data(), unpacked.size());
    for (std::size_t i = 0; i < points; ++i)
      store(i, [&](const Field& f) {
        return load_ply_scalar(f.scalar, bytes.data() + f.offset * points + i * f.size * f.count, false);
      });
    return raw;
  }
  for (std::size_t i = 0; i < points; ++i)
    store(i, [&](const Field& f) { return load_ply_scalar(f.scalar, bytes.data() + i * h.record + f.offset, false); });
  return raw;
}

std::optional<StreamHeader> pcd_stream_header(const Source& src) {
  if (!sniff_pcd(src.bytes)) return std::nullopt;
  PcdHeader h;
  read_header(src, h);
  if (h.data == "binary_compressed") return std::nullopt;  // LZF unpacks the whole body at once: read whole
  return StreamHeader{.count = h.points,
                      .has_normals = h.has_normals,
                      .has_colors = h.rgb != nullptr,
                      .format = "pcd " + h.data,
                      .other_attributes = h.other_attributes,
                      .stream = stream_pcd};
}

std::optional<std::uint64_t> pcd_header_count(const Source& src) {
  if (!sniff_pcd(src.bytes)) return std::nullopt;
  PcdHeader h;
  read_header(src, h);
  return h.points;
}

void stream_pcd(const Source& src, std::size_t chunk_points, PointSink& sink) {
  PcdHeader h;
  read_header(src, h);
  if (h.data == "ascii") {
    AsciiRows rows(src, h);
    stream_chunks(
        src, h.points, chunk_points, h.has_normals, h.rgb != nullptr, sink,
        [&](std::uint64_t i, Vec3d& p, Vec3f* n, Rgb8* c) { rows.read(i, p, n, c); },
        [&](std::uint64_t) { return rows.end(); });
    return;
  }
  stream_chunks(
      src, h.points, chunk_points, h.has_normals, h.rgb != nullptr, sink,
      [&](std::uint64_t i, Vec3d& p, Vec3f* n, Rgb8* c) {
        const char* r = src.bytes.data() + h.body + i * h.record;
        decode(h, [&](const Field& f) { return load_ply_scalar(f.scalar, r + f.offset, false); }, p, n, c);
      },
      [&](std::uint64_t end) { return h.body + static_cast<std::size_t>(end) * h.record; }, Decode::any_order);
}

}  // namespace pcsketch::io::detail
