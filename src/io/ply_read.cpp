// PLY reader: ascii, binary_little_endian, binary_big_endian; every scalar type and alias; any elements and list
// properties (skipped unless they are the vertices or, for meshes, the faces).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <utility>

#include "ply_types.h"
#include "point_stream.h"
#include "raw_cloud.h"
#include "text_scan.h"

namespace pcsketch::io::detail {
namespace {

enum class Encoding : std::uint8_t { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Property {
  std::string name;
  PlyScalar type = PlyScalar::F32;      ///< the value type (items, for a list)
  std::optional<PlyScalar> count_type;  ///< set for a list property
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t line = 0;  ///< header line declaring it
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;
  std::uint64_t body_line = 0;  ///< line number of the first body line (ascii)
};

Header parse_header(const Source& src) {
  LineReader lines(src.bytes, 1, src.path);
  std::string_view line;
  lines.next(line);
  Header h;
  bool have_format = false;
  while (true) {
    if (!lines.next(line)) src.fail_at_line(lines.line() + 1, "PLY: header has no end_header line");
    Tokens tokens(line, false);
    std::string_view keyword;
    if (!tokens.next(keyword) || keyword == "comment" || keyword == "obj_info") continue;
    const auto fail = [&](const std::string& message) { src.fail_at_line(lines.line(), "PLY: " + message); };
    std::string_view a, b, c, d;
    if (keyword == "end_header") {
      break;
    } else if (keyword == "format") {
      if (!tokens.next(a) || !tokens.next(b)) fail("format line needs an encoding and a version");
      if (a == "ascii") {
        h.encoding = Encoding::Ascii;
      } else if (a == "binary_little_endian") {
        h.encoding = Encoding::BinaryLittleEndian;
      } else if (a == "binary_big_endian") {
        h.encoding = Encoding::BinaryBigEndian;
      } else {
        fail("unknown format " + quote(a));
      }
      have_format = true;
    } else if (keyword == "element") {
      std::uint64_t count = 0;
      if (!tokens.next(a) || !tokens.next(b) || !parse_uint(b, count))
        fail("element line needs a name and a non-negative count");
      h.elements.push_back(Element{std::string(a), count, lines.line(), {}});
    } else if (keyword == "property") {
      if (h.elements.empty()) fail("property before any element");
      Property p;
      if (!tokens.next(a)) fail("property line needs a type and a name");
      if (a == "list") {
        if (!tokens.next(b) || !tokens.next(c) || !tokens.next(d)) fail("list property needs two types and a name");
        const auto count_type = ply_scalar_from_name(b);
        const auto item_type = ply_scalar_from_name(c);
        if (!count_type || !item_type) fail("unknown type in list property " + quote(d));
        if (*count_type == PlyScalar::F32 || *count_type == PlyScalar::F64)
          fail("list count type of " + quote(d) + " must be an integer type");
        p = Property{std::string(d), *item_type, count_type};
      } else {
        const auto type = ply_scalar_from_name(a);
        if (!type || !tokens.next(b)) fail("property needs a known type and a name, got " + quote(line));
        p = Property{std::string(b), *type, std::nullopt};
      }
      h.elements.back().properties.push_back(std::move(p));
    } else {
      fail("unknown header keyword " + quote(keyword));
    }
  }
  if (!have_format) src.fail_at_line(lines.line(), "PLY: header has no format line");
  h.body_offset = lines.consumed(src.bytes);
  h.body_line = lines.line() + 1;
  return h;
}

// Checks every element's count against the bytes left, before anything is allocated or looped over.
void check_counts(const Source& src, const Header& h) {
  const std::uint64_t available = src.bytes.size() - h.body_offset;
  // An ascii file may end right after its last value, without a separator.
  const std::uint64_t budget = available + (h.encoding == Encoding::Ascii ? 1 : 0);
  std::uint64_t needed = 0;
  for (const Element& e : h.elements) {
    if (e.count == 0) continue;
    if (e.properties.empty())
      src.fail_at_line(e.line, "PLY: element " + quote(e.name) + " has entries but no properties");
    // Smallest possible entry: binary, every scalar and list count once (lists empty); ascii, one digit and one
    // separator per value.
    std::uint64_t min_entry = 0;
    for (const Property& p : e.properties)
      min_entry += h.encoding == Encoding::Ascii ? 2 : ply_scalar_size(p.count_type.value_or(p.type));
    // Invariant: needed <= budget, so the subtraction cannot wrap and the product below cannot overflow.
    if (e.count > (budget - needed) / min_entry)
      src.fail_at_byte(h.body_offset, "PLY: element " + quote(e.name) + " claims " + std::to_string(e.count) +
                                          " entries of at least " + std::to_string(min_entry) + " bytes, but only " +
                                          std::to_string(available) + " bytes follow the header (truncated body?)");
    needed += e.count * min_entry;
  }
}

// Where a property's values go: a vertex coordinate slot or a face index list.
constexpr int kSkip = -1;

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

  /// Skips `e` entirely.
  void skip(const Element& e) {
    if (e.count == 0) return;  // may have no properties at all
    const bool fixed = std::none_of(e.properties.begin(), e.properties.end(),
                                    [](const Property& p) { return p.count_type.has_value(); });
    if (binary() && fixed) {
      // check_counts() bounded each element by its smallest entries only; a list before this one may have eaten
      // into the bytes it counted on, so check again.
      std::uint64_t stride = 0;
      for (const Property& p : e.properties) stride += ply_scalar_size(p.type);
      if (e.count > remaining() / stride) truncated(e, e.properties.back());
      pos_ += e.count * stride;
      return;
    }
    const std::vector<int> slots(e.properties.size(), kSkip);
    std::vector<std::uint32_t> unused;
    for (std::uint64_t i = 0; i < e.count; ++i) entry(e, slots, nullptr, kSkip, unused);
  }

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

/// One vertex entry into position, normal and colour.
void read_vertex(BodyReader& body, const Element& e, const VertexLayout& l, Vec3d& p, Vec3f* n, Rgb8* c) {
  std::array<double, 9> v{};
  std::vector<std::uint32_t> unused;
  body.entry(e, l.slots, v.data(), kSkip, unused);
  p = Vec3d(v[0], v[1], v[2]);
  if (n != nullptr) *n = Vec3f(float(v[3]), float(v[4]), float(v[5]));
  if (c != nullptr)
    *c = {to_color(v[6], e.properties[l.columns[6]].type), to_color(v[7], e.properties[l.columns[7]].type),
          to_color(v[8], e.properties[l.columns[8]].type)};
}

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
      for (std::uint64_t i = 0; i < e.count; ++i)
        read_vertex(body, e, layout, raw.positions[i], has_normals ? &raw.normals[i] : nullptr,
                    has_colors ? &raw.colors[i] : nullptr);
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
