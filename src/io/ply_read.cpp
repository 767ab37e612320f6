// PLY reader: ascii, binary_little_endian, binary_big_endian; every scalar type and alias; any elements and list
// properties (skipped unless they are the vertices or, for meshes, the faces).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <utility>

#include "ply_header.h"
#include "ply_types.h"
#include "point_stream.h"
#include "raw_cloud.h"
#include "text_scan.h"

namespace pcsketch::io::detail {
namespace {

// Where a property's values go: a vertex coordinate slot or a face index list.
constexpr int kSkip = -1;

/// Bytes of one binary entry of `e`, or 0 if its entries differ in size (a list property).
std::size_t entry_size(const Element& e) {
  std::size_t stride = 0;
  for (const Property& p : e.properties) {
    if (p.count_type) return 0;
    stride += ply_scalar_size(p.type);
  }
  return stride;
}

/// Reads element entries one after another; binary and ascii share the per-entry walk.
class BodyReader {
 public:
  BodyReader(const Source& src, const Header& h)
      : src_(src), h_(h), pos_(h.body_offset), tokens_(src.bytes.substr(h.body_offset), h.body_line, false, src.path) {
    swap_ = h.encoding != Encoding::Ascii &&
            (h.encoding == Encoding::BinaryBigEndian) != (std::endian::native == std::endian::big);
  }

  /// One entry of `e`: scalar property j goes to values[slots[j]] unless the slot is kSkip; the items of list
  /// property `list_slot` (if any) go to `list`.
  void entry(const Element& e, const std::vector<int>& slots, double* values, int list_slot,
             std::vector<std::uint32_t>& list) {
    entry_start_ = true;
    for (std::size_t j = 0; j < e.properties.size(); ++j) {
      const Property& p = e.properties[j];
      if (!p.count_type) {
        const double v = scalar(p.type, e, p);
        if (slots[j] != kSkip) values[slots[j]] = v;
        continue;
      }
      const std::uint64_t n = count(*p.count_type, e, p);
      const bool keep = static_cast<int>(j) == list_slot;
      if (keep) list.clear();
      if (binary() && !keep) {
        const std::uint64_t bytes = n * ply_scalar_size(p.type);
        if (n > remaining() || bytes > remaining()) truncated(e, p);
        pos_ += bytes;
        continue;
      }
      for (std::uint64_t i = 0; i < n; ++i) {
        const double v = scalar(p.type, e, p);
        if (keep) {
          if (!(v >= 0 && v <= 4294967295.0) || v != std::floor(v))
            fail(e, "list item of " + quote(p.name) + " is not a valid index");
          list.push_back(static_cast<std::uint32_t>(v));
        }
      }
    }
    // An ascii entry is one line: a value too many would shift every later value into the wrong property.
    if (!binary() && !tokens_.line_done())
      fail(e, "more values on the line than the header's " + std::to_string(e.properties.size()) + " properties");
  }

  /// Binary entries of `e` all of one size (no list property): passes over them all and returns the first one's
  /// offset, once their bytes are known to be in the file; nullopt otherwise, nothing read.
  std::optional<std::size_t> take_fixed(const Element& e) {
    const std::size_t stride = entry_size(e);
    if (!binary() || stride == 0) return std::nullopt;
    // check_counts() bounded each element by its smallest entries only; a list before this one may have eaten
    // into the bytes it counted on, so check again.
    if (e.count > remaining() / stride) truncated(e, e.properties.back());
    const std::size_t first = pos_;
    pos_ += e.count * stride;
    return first;
  }

  /// Skips `e` entirely.
  void skip(const Element& e) {
    if (e.count == 0) return;  // may have no properties at all
    if (take_fixed(e)) return;
    const std::vector<int> slots(e.properties.size(), kSkip);
    std::vector<std::uint32_t> unused;
    for (std::uint64_t i = 0; i < e.count; ++i) entry(e, slots, nullptr, kSkip, unused);
  }

  bool swapped() const { return swap_; }

  /// Offset of the first byte not read yet (ascii: past the line of the last value).
  std::size_t position() const { return binary() ? pos_ : h_.body_offset + tokens_.offset(); }

  [[noreturn]] void fail(const Element& e, const std::string& message) const {
    if (binary()) src_.fail_at_byte(pos_, "PLY: element " + quote(e.name) + ": " + message);
    src_.fail_at_line(tokens_.line(), "PLY: element " + quote(e.name) + ": " + message);
  }

 private:
  bool binary() const { return h_.encoding != Encoding::Ascii; }
  std::uint64_t remaining() const { return src_.bytes.size() - pos_; }

  [[noreturn]] void truncated(const Element& e, const Property& p) const {
    fail(e, "file ends in the middle of property " + quote(p.name) + " (truncated body)");
  }

  double scalar(PlyScalar type, const Element& e, const Property& p) {
    if (binary()) {
      const std::size_t size = ply_scalar_size(type);
      if (size > remaining()) truncated(e, p);
      const double v = load_ply_scalar(type, src_.bytes.data() + pos_, swap_);
      pos_ += size;
      return v;
    }
    // An ascii entry is one line: its first value starts a line, the others may not take the next line's.
    std::string_view token;
    const bool first = std::exchange(entry_start_, false);
    if (first && !tokens_.next(token)) fail(e, "file ends before property " + quote(p.name) + " (truncated body)");
    if (!first && !tokens_.next_on_line(token))
      fail(e, "too few values on the line: it ends before property " + quote(p.name));
    double v = 0;
    if (!parse_double(token, v)) fail(e, bad_number(token) + " for property " + quote(p.name));
    return v;
  }

  std::uint64_t count(PlyScalar type, const Element& e, const Property& p) {
    const double v = scalar(type, e, p);
    if (!(v >= 0) || v != std::floor(v) || v > 4294967295.0) fail(e, "invalid list count for " + quote(p.name));
    return static_cast<std::uint64_t>(v);
  }

  const Source& src_;
  const Header& h_;
  std::size_t pos_;
  TokenStream tokens_;
  bool entry_start_ = false;  ///< ascii: the next value is an entry's first, on a line of its own
  bool swap_ = false;
};

/// The first element called `name`, or nullptr.
const Element* find_element(const Header& h, std::string_view name) {
  const auto it = std::find_if(h.elements.begin(), h.elements.end(), [&](const Element& e) { return e.name == name; });
  return it == h.elements.end() ? nullptr : &*it;
}

int find_property(const Element& e, std::initializer_list<std::string_view> names) {
  for (std::size_t j = 0; j < e.properties.size(); ++j)
    if (!e.properties[j].count_type && std::find(names.begin(), names.end(), e.properties[j].name) != names.end())
      return static_cast<int>(j);
  return kSkip;
}

// Colours stored as floats are in [0, 1]; integer colours in [0, 255].
std::uint8_t to_color(double v, PlyScalar type) {
  return to_channel(type == PlyScalar::F32 || type == PlyScalar::F64 ? v * 255.0 : v);
}

const Element& vertex_element(const Source& src, const Header& h) {
  const Element* vertex = find_element(h, "vertex");
  if (vertex == nullptr) src.fail("PLY: no \"vertex\" element in the header");
  if (vertex->count > 0xffffffffull) src.fail_at_line(vertex->line, "PLY: more than 2^32-1 vertices");
  return *vertex;
}

// Where each vertex property goes. Slots: 0-2 position, 3-5 normal, 6-8 colour.
struct VertexLayout {
  std::array<int, 9> columns{};
  bool has_normals = false;
  bool has_colors = false;
  std::vector<int> slots;  ///< per property: its slot or kSkip
};

VertexLayout vertex_layout(const Source& src, const Element& vertex) {
  VertexLayout l;
  l.columns = {find_property(vertex, {"x"}),
               find_property(vertex, {"y"}),
               find_property(vertex, {"z"}),
               find_property(vertex, {"nx", "normal_x"}),
               find_property(vertex, {"ny", "normal_y"}),
               find_property(vertex, {"nz", "normal_z"}),
               find_property(vertex, {"red", "diffuse_red"}),
               find_property(vertex, {"green", "diffuse_green"}),
               find_property(vertex, {"blue", "diffuse_blue"})};
  const auto& columns = l.columns;
  if (columns[0] == kSkip || columns[1] == kSkip || columns[2] == kSkip)
    src.fail_at_line(vertex.line, "PLY: element \"vertex\" lacks one of the scalar properties x, y, z");
  l.has_normals = columns[3] != kSkip && columns[4] != kSkip && columns[5] != kSkip;
  l.has_colors = columns[6] != kSkip && columns[7] != kSkip && columns[8] != kSkip;
  l.slots.assign(vertex.properties.size(), kSkip);
  for (int s = 0; s < 9; ++s)
    if (columns[s] != kSkip && (s < 3 || (s < 6 ? l.has_normals : l.has_colors))) l.slots[columns[s]] = s;
  return l;
}

std::string format_name(const Header& h) {
  return std::string("ply ") + (h.encoding == Encoding::Ascii                ? "ascii"
                                : h.encoding == Encoding::BinaryLittleEndian ? "binary_little_endian"
                                                                             : "binary_big_endian");
}

std::vector<std::string> skipped_properties(const Element& vertex, const VertexLayout& l) {
  std::vector<std::string> out;
  for (std::size_t j = 0; j < vertex.properties.size(); ++j)
    if (l.slots[j] == kSkip) out.push_back(vertex.properties[j].name);
  return out;
}

/// A vertex's slots (VertexLayout) into position, normal and colour.
void store_vertex(const std::array<double, 9>& v, const Element& e, const VertexLayout& l, Vec3d& p, Vec3f* n,
                  Rgb8* c) {
  p = Vec3d(v[0], v[1], v[2]);
  if (n != nullptr) *n = Vec3f(float(v[3]), float(v[4]), float(v[5]));
  if (c != nullptr)
    *c = {to_color(v[6], e.properties[l.columns[6]].type), to_color(v[7], e.properties[l.columns[7]].type),
          to_color(v[8], e.properties[l.columns[8]].type)};
}

/// One vertex entry into position, normal and colour.
void read_vertex(BodyReader& body, const Element& e, const VertexLayout& l, Vec3d& p, Vec3f* n, Rgb8* c) {
  std::array<double, 9> v{};
  std::vector<std::uint32_t> unused;
  body.entry(e, l.slots, v.data(), kSkip, unused);
  store_vertex(v, e, l, p, n, c);
}

/// Binary vertex entries of one size, each decoded on its own from its offset: in parallel, where the walk of
/// read_vertex is serial (the 100M-point file's streamed read 14.4–15.5 → 10.0–10.3 s, docs/io.md).
class FixedVertices {
 public:
  /// The vertex entries from `first` (BodyReader::take_fixed).
  FixedVertices(const Source& src, const Element& e, const VertexLayout& l, std::size_t first, bool swap)
      : base_(src.bytes.data() + first), first_(first), stride_(entry_size(e)), e_(e), l_(l), swap_(swap) {
    std::size_t offset = 0;
    for (std::size_t j = 0; j < e.properties.size(); ++j) {
      if (l.slots[j] != kSkip) fields_.push_back({offset, e.properties[j].type, l.slots[j]});
      offset += ply_scalar_size(e.properties[j].type);
    }
  }

  void read(std::uint64_t i, Vec3d& p, Vec3f* n, Rgb8* c) const {
    std::array<double, 9> v{};
    const char* entry = base_ + i * stride_;
    for (const Field& f : fields_)
      v[static_cast<std::size_t>(f.slot)] = load_ply_scalar(f.type, entry + f.offset, swap_);
    store_vertex(v, e_, l_, p, n, c);
  }

  /// Offset where the first `count` entries end.
  std::size_t end(std::uint64_t count) const { return first_ + static_cast<std::size_t>(count) * stride_; }

 private:
  struct Field {
    std::size_t offset;
    PlyScalar type;
    int slot;
  };
  const char* base_;
  std::size_t first_, stride_;
  const Element& e_;
  const VertexLayout& l_;
  bool swap_;
  std::vector<Field> fields_;
};

}  // namespace

std::optional<StreamHeader> ply_stream_header(const Source& src) {
  if (!src.bytes.starts_with("ply\n") && !src.bytes.starts_with("ply\r\n")) return std::nullopt;
  const Header h = parse_header(src);
  check_counts(src, h);
  const Element& vertex = vertex_element(src, h);
  const VertexLayout l = vertex_layout(src, vertex);
  return StreamHeader{vertex.count, l.has_normals, l.has_colors, format_name(h), skipped_properties(vertex, l),
                      stream_ply};
}

std::optional<std::uint64_t> ply_header_count(const Source& src) {
  if (!src.bytes.starts_with("ply\n") && !src.bytes.starts_with("ply\r\n")) return std::nullopt;
  const Header h = parse_header(src);
  check_counts(src, h);
  return vertex_element(src, h).count;
}

void stream_ply(const Source& src, std::size_t chunk_points, PointSink& sink) {
  const Header h = parse_header(src);
  check_counts(src, h);
  const Element& vertex = vertex_element(src, h);
  const VertexLayout l = vertex_layout(src, vertex);
  BodyReader body(src, h);
  for (const Element& e : h.elements) {
    if (&e == &vertex) break;
    body.skip(e);
  }
  if (const std::optional<std::size_t> first = body.take_fixed(vertex)) {
    const FixedVertices entries(src, vertex, l, *first, body.swapped());
    stream_chunks(
        src, vertex.count, chunk_points, l.has_normals, l.has_colors, sink,
        [&](std::uint64_t i, Vec3d& p, Vec3f* n, Rgb8* c) { entries.read(i, p, n, c); },
        [&](std::uint64_t end) { return entries.end(end); }, Decode::any_order);
    return;
  }
  // The vertices are read in order, so the body reader's position is where the points read so far end.
  stream_chunks(
      src, vertex.count, chunk_points, l.has_normals, l.has_colors, sink,
      [&](std::uint64_t, Vec3d& p, Vec3f* n, Rgb8* c) { read_vertex(body, vertex, l, p, n, c); },
      [&](std::uint64_t) { return body.position(); });
}

RawCloud parse_ply(const Source& src, Want want) {
  const Header h = parse_header(src);
  check_counts(src, h);
  const Element& vertex = vertex_element(src, h);

  const VertexLayout layout = vertex_layout(src, vertex);
  const bool has_normals = layout.has_normals, has_colors = layout.has_colors;
  RawCloud raw;
  raw.format = format_name(h);
  raw.other_attributes = skipped_properties(vertex, layout);

  const Element* face = nullptr;
  int face_list = kSkip;
  if (want == Want::Mesh) {
    // The first "face" element, with its own list (a later one is skipped like any other element).
    face = find_element(h, "face");
    if (face == nullptr) src.fail("PLY: no \"face\" element in the header; it is not a mesh");
    for (std::size_t j = 0; j < face->properties.size(); ++j)
      if (face->properties[j].count_type &&
          (face->properties[j].name == "vertex_indices" || face->properties[j].name == "vertex_index"))
        face_list = static_cast<int>(j);
    if (face_list == kSkip) src.fail_at_line(face->line, "PLY: element \"face\" has no list property vertex_indices");
  }

  BodyReader body(src, h);
  bool vertices_done = false, faces_done = face == nullptr;
  std::vector<std::uint32_t> polygon;
  for (const Element& e : h.elements) {
    if (vertices_done && faces_done) break;
    if (&e == &vertex) {
      raw.positions.resize(e.count);
      if (has_normals) raw.normals.resize(e.count);
      if (has_colors) raw.colors.resize(e.count);
      Vec3f* normals = has_normals ? raw.normals.data() : nullptr;
      Rgb8* colors = has_colors ? raw.colors.data() : nullptr;
      const auto count = static_cast<std::size_t>(e.count);
      if (const std::optional<std::size_t> first = body.take_fixed(e)) {
        const FixedVertices entries(src, e, layout, *first, body.swapped());
        decode_points(
            0, count, [&](std::uint64_t i, Vec3d& p, Vec3f* n, Rgb8* c) { entries.read(i, p, n, c); },
            raw.positions.data(), normals, colors, Decode::any_order);
      } else {
        decode_points(
            0, count, [&](std::uint64_t, Vec3d& p, Vec3f* n, Rgb8* c) { read_vertex(body, e, layout, p, n, c); },
            raw.positions.data(), normals, colors, Decode::file_order);
      }
      vertices_done = true;
    } else if (&e == face) {
      const std::vector<int> none(e.properties.size(), kSkip);
      for (std::uint64_t i = 0; i < e.count; ++i) {
        body.entry(e, none, nullptr, face_list, polygon);
        for (const std::uint32_t index : polygon)
          if (index >= vertex.count)
            body.fail(e, "face " + std::to_string(i) + " uses vertex " + std::to_string(index) + " of " +
                             std::to_string(vertex.count));
        add_fan(polygon, raw.faces);
      }
      faces_done = true;
    } else {
      body.skip(e);
    }
  }
  return raw;
}

}  // namespace pcsketch::io::detail
