#include "ply_header.h"

#include "text_scan.h"

namespace pcsketch::io::detail {

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

}  // namespace pcsketch::io::detail
